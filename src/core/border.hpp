// core/border.hpp - whole-sample symmetric reflection (OpenCV's
// BORDER_REFLECT_101), shared by pyrDown and the symmetric lifting wavelets.
#pragma once

namespace vkfuse::core {

// Maps any integer position onto 0..n-1 by reflecting about the end samples
// without repeating them: -1 -> 1, -2 -> 2, n -> n - 2, n + 1 -> n - 3; repeats
// until inside (short lines). n == 1 maps everything to 0. For n >= 2 the
// result has the parity of p (the period 2n - 2 is even), which is what lets
// lifting steps read odd neighbours from odd samples only.
inline int reflect101(int p, int n) {
    if (n == 1) return 0;
    while (p < 0 || p >= n) p = p < 0 ? -p : 2 * n - 2 - p;
    return p;
}

}  // namespace vkfuse::core
