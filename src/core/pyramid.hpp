// core/pyramid.hpp - OpenCV's cv::pyrDown / cv::pyrUp(dstsize) on one double
// plane, exactly (OpenCV 4.6, default border), written in gather form: every
// output sample is a weighted sum of source samples at computed indices, so the
// GPU shaders port these formulas one to one. Verified against cv2 4.6 on
// CV_64F for every size 1..11 plus 61, 64 x 1..11 plus 48, 97 (max error 3e-16).
//
// pyr_down(src: h x w) -> ((h + 1) / 2) x ((w + 1) / 2):
//   k = [1, 4, 6, 4, 1]
//   out[y][x] = sum_{a=0..4} sum_{b=0..4} k[a] k[b] src[R(2y + a - 2, h)][R(2x + b - 2, w)] / 256
//   R(p, n) = reflect101 (core/border.hpp), BORDER_REFLECT_101: n == 1 -> 0; else repeat { p < 0 -> -p; p >= n -> 2n - 2 - p }
//             until 0 <= p < n   (-1 -> 1, -2 -> 2, n -> n - 2, n + 1 -> n - 3).
//
// pyr_up(src: h x w, H, W) with H in {2h - 1, 2h} and W in {2w - 1, 2w}:
//   separable; along one axis (source length n, output index X, j = X / 2):
//     X even: (s[E(j - 1)] + 6 s[j] + s[E(j + 1)]) / 8
//     X odd:  (s[j] + s[E(j + 1)]) / 2            (= 4 (s[j] + s[E(j+1)]) / 8)
//   E(i) = OpenCV's pyrUp edge rule, NOT plain reflect-101:
//     i < 0  -> min(1, n - 1)   (left/top: reflect-101; a length-1 axis replicates)
//     i >= n -> n - 1           (right/bottom: replicate)
//     else i
//   so out[0] = (6 s0 + 2 s1) / 8, out[2n-2] = (s[n-2] + 7 s[n-1]) / 8, out[2n-1] = s[n-1].
//   out[Y][X] = sum over the (up to 3) row taps wy and column taps wx of wy wx src[row][col].
//   An odd size 2n - 1 simply stops before index 2n - 1: the last sample is the
//   even formula (s[n-2] + 7 s[n-1]) / 8 (OpenCV 4.6 writes t1 then t0 into the
//   same row, so t0 wins; no special case). OpenCV also accepts 2n + 1 with an
//   odd row-copy special case; the Laplacian never asks for it, so pyr_up rejects it.
#pragma once
#include "core/plane.hpp"

namespace vkfuse::core {

Plane pyr_down(const Plane& src);
// Throws std::invalid_argument unless dst_h in {2h-1, 2h} and dst_w in {2w-1, 2w}.
Plane pyr_up(const Plane& src, int dst_h, int dst_w);

}  // namespace vkfuse::core
