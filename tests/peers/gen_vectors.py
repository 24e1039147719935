#!/usr/bin/python3
"""Peer vectors for the CPU reference path: what PyWavelets, OpenCV and numpy
(docs/spec.md's formulas) compute, written to tests/data/peers/*.bin so the C++
tests compare against them without Python at run time.

Run with Debian's interpreter (it has python3-pywt, python3-opencv, numpy):
    /usr/bin/python3 tests/peers/gen_vectors.py
Deterministic: fixed seeds, no time or environment dependence.

File format (little-endian), read by tests/peer_file.hpp:
    b"VKPEER01", uint32 record count, then per record:
    uint32 name length, name (UTF-8), uint32 dtype (0 float64, 1 float32, 2 uint8),
    uint32 ndim, ndim x uint32 shape, the values in C order.
Inputs are stored as float32 (every random input is float32-representable, so
nothing is lost); results the tests compare are float64.
"""
import os
import struct
import sys

import cv2
import numpy as np
import pywt

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "..", "data", "peers")
DIGIT = os.path.join(HERE, "..", "data", "digit_bg_tacto.png")

WAVELETS = ["haar", "db2", "bior2.2", "bior4.4"]
RULES = ["max-abs", "mean", "max", "min"]
DTYPES = {np.dtype("float64"): 0, np.dtype("float32"): 1, np.dtype("uint8"): 2}


def write(name, records):
    path = os.path.join(OUT, name)
    with open(path, "wb") as f:
        f.write(b"VKPEER01")
        f.write(struct.pack("<I", len(records)))
        for key, arr in records:
            arr = np.ascontiguousarray(arr)
            if arr.dtype not in DTYPES:
                raise TypeError(f"{key}: dtype {arr.dtype}")
            raw = key.encode()
            f.write(struct.pack("<I", len(raw)) + raw)
            f.write(struct.pack("<II", DTYPES[arr.dtype], arr.ndim))
            f.write(struct.pack(f"<{arr.ndim}I", *arr.shape))
            f.write(arr.astype(arr.dtype.newbyteorder("<")).tobytes())
    print(f"{path}: {len(records)} records, {os.path.getsize(path)} bytes")


def rand(rng, *shape):
    """Uniform [0, 1) values that are exact in float32."""
    return rng.random(shape).astype(np.float32)


def size_key(a):
    return "x".join(str(s) for s in a.shape)


# ---------------------------------------------------------------- rules, docs/spec.md
def combine(rule, stack):
    """A rule across axis 0 (the frames). argmax returns the first maximum, so
    max-abs ties go to the lowest frame index, as docs/spec.md requires."""
    if rule == "max-abs":
        idx = np.argmax(np.abs(stack), axis=0)
        return np.take_along_axis(stack, idx[None], axis=0)[0]
    if rule == "mean":
        return np.mean(stack, axis=0)
    if rule == "max":
        return np.max(stack, axis=0)
    return np.min(stack, axis=0)


# -------------------------------------------- modified coefficients (synthesis)
def perturbation(n, band):
    """Reproducible in C++ with exact integer arithmetic: u in [-0.5, 0.5)."""
    i = np.arange(n, dtype=np.uint64)
    h = ((i + np.uint64(1)) * np.uint64(2654435761) + np.uint64(band) * np.uint64(40503)) % np.uint64(2**32)
    return h.astype(np.float64) / 2.0**32 - 0.5


def modify(coeffs):
    """0.5 * c + u(band) for every band, bands numbered approx = 0, then
    level l (1 = finest) band b (0 h, 1 v, 2 d) = 1 + 3 (l - 1) + b."""
    levels = len(coeffs) - 1
    out = [0.5 * coeffs[0] + perturbation(coeffs[0].size, 0).reshape(coeffs[0].shape)]
    for pos, bands in enumerate(coeffs[1:]):
        level = levels - pos
        out.append(tuple(0.5 * c + perturbation(c.size, 1 + 3 * (level - 1) + b).reshape(c.shape)
                         for b, c in enumerate(bands)))
    return out


def wavelet_vectors(rng):
    records = []
    for h, w in [(16, 16), (33, 47), (61, 97), (64, 48)]:
        x = rand(rng, h, w)
        records.append((f"input/{h}x{w}", x))
        for wav in WAVELETS:
            top = pywt.dwt_max_level(min(h, w), pywt.Wavelet(wav).dec_len)
            if top == 0:
                continue
            c = pywt.wavedec2(x.astype(np.float64), wav, mode="periodization", level=top)
            base = f"{wav}/{h}x{w}"
            records.append((f"{base}/L{top}/approx", c[0]))
            for pos, (ch, cv, cd) in enumerate(c[1:]):
                level = top - pos
                records += [(f"{base}/L{top}/level{level}/h", ch), (f"{base}/L{top}/level{level}/v", cv),
                            (f"{base}/L{top}/level{level}/d", cd)]
            # Every level count on the small sizes; the shallowest and deepest on
            # the large ones (keeps the vectors small).
            counts = range(1, top + 1) if h * w < 2000 else sorted({1, top})
            for L in counts:
                cl = pywt.wavedec2(x.astype(np.float64), wav, mode="periodization", level=L)
                rec = pywt.waverec2(modify(cl), wav, mode="periodization")
                records.append((f"{base}/L{L}/rec_modified", rec[:h, :w]))
                # pywt returns an even size for odd inputs; the extra row/column
                # is dropped by vkfuse (the fused image keeps the input shape).
    # pywt.dwt_max_level(n, dec_len) for n = 1..300: the level bound validate() uses.
    for wav in WAVELETS:
        dec_len = pywt.Wavelet(wav).dec_len
        records.append((f"max_level/{wav}", np.array([pywt.dwt_max_level(n, dec_len) for n in range(1, 301)],
                                                     dtype=np.float64)))
    # The filter banks themselves, so a typo in the C++ tables cannot hide.
    for wav in WAVELETS:
        records.append((f"filter_bank/{wav}", np.array(pywt.Wavelet(wav).filter_bank, dtype=np.float64)))
    write("wavelet_periodization.bin", records)


# ------------------------------------------------------------------ pyramids
def pyramid_vectors(rng):
    records = []
    for h, w in [(1, 1), (1, 5), (5, 1), (2, 3), (5, 7), (61, 97), (64, 48)]:
        x = rand(rng, h, w)
        key = f"{h}x{w}"
        records.append((f"{key}/input", x))
        down = cv2.pyrDown(x.astype(np.float64))
        records.append((f"{key}/down", down))
        if h * w <= 64:
            # Small sources: every parity of dstsize, 2n and 2n - 1 per axis.
            for H in (2 * h, 2 * h - 1):
                for W in (2 * w, 2 * w - 1):
                    up = cv2.pyrUp(x.astype(np.float64), dstsize=(W, H))
                    records.append((f"{key}/up_{H}x{W}", up))
        else:
            # Large sources: what the Laplacian does, pyrUp of pyrDown back to
            # the original (odd or even) size, and to the other parity.
            dh, dw = down.shape
            for H, W in [(h, w), (2 * dh - (h % 2 == 0), 2 * dw - (w % 2 == 0))]:
                records.append((f"{key}/down_up_{H}x{W}", cv2.pyrUp(down, dstsize=(W, H))))
    write("pyramid.bin", records)


# -------------------------------------------------------------- fusion, docs/spec.md
def planes(frames):
    """(K, H, W, C) -> list over channels of (K, H, W)."""
    return [frames[..., c] for c in range(frames.shape[-1])]


def fuse_wavelet(frames, wav, L, base, detail):
    out = []
    for stack in planes(frames):
        cs = [pywt.wavedec2(f, wav, mode="periodization", level=L) for f in stack]
        fused = [combine(base, np.stack([c[0] for c in cs]))]
        for lev in range(1, L + 1):
            fused.append(tuple(combine(detail, np.stack([c[lev][b] for c in cs])) for b in range(3)))
        out.append(pywt.waverec2(fused, wav, mode="periodization")[:stack.shape[1], :stack.shape[2]])
    return np.stack(out, axis=-1)


def laplacian_pyramid(g, L):
    lap = []
    for _ in range(L):
        nxt = cv2.pyrDown(g)
        lap.append(g - cv2.pyrUp(nxt, dstsize=(g.shape[1], g.shape[0])))
        g = nxt
    return lap + [g]


def fuse_laplacian(frames, L, base, detail):
    out = []
    for stack in planes(frames):
        pyrs = [laplacian_pyramid(f, L) for f in stack]
        fused = [combine(detail if l < L else base, np.stack([p[l] for p in pyrs])) for l in range(L + 1)]
        r = fused[L]
        for l in range(L - 1, -1, -1):
            r = cv2.pyrUp(r, dstsize=(fused[l].shape[1], fused[l].shape[0])) + fused[l]
        out.append(r)
    return np.stack(out, axis=-1)


def fuse_brovey(frames):
    p = np.maximum(frames, 0.0)
    s = p.sum(axis=0)
    safe = np.where(s >= 1e-6, s, 1.0)
    ratio = (p / safe * frames).sum(axis=0)
    return np.where(s >= 1e-6, ratio, frames.mean(axis=0))


def fusion_vectors(rng):
    records = []

    def case(name, frames, fused):
        records.append((f"{name}/frames", frames))
        records.append((f"{name}/fused", fused))

    # Every rule pair, K = 3, one channel, odd sizes.
    f = rand(rng, 3, 37, 41, 1)
    records.append(("rules/frames", f))
    f64 = f.astype(np.float64)
    for base in RULES:
        for detail in RULES:
            records.append((f"rules/wavelet/bior4.4/L2/{base}/{detail}", fuse_wavelet(f64, "bior4.4", 2, base, detail)))
            records.append((f"rules/laplacian/L4/{base}/{detail}", fuse_laplacian(f64, 4, base, detail)))
    # Default rules, RGB, each wavelet at its deepest level and at 1 level.
    f = rand(rng, 2, 29, 38, 3)
    records.append(("wavelet/29x38x3/frames", f))
    for wav in WAVELETS:
        top = pywt.dwt_max_level(29, pywt.Wavelet(wav).dec_len)
        for L in sorted({1, top}):
            records.append((f"wavelet/29x38x3/{wav}/L{L}", fuse_wavelet(f.astype(np.float64), wav, L, "mean", "max-abs")))
    # Laplacian at sizes where OpenCV's odd-size and tiny-size handling shows.
    for shape, L in [((4, 61, 97, 1), 5), ((2, 1, 7, 3), 4), ((2, 6, 1, 1), 3), ((3, 8, 8, 3), 4), ((2, 1, 1, 1), 2)]:
        f = rand(rng, *shape)
        key = "x".join(str(s) for s in shape[1:])
        case(f"laplacian/L{L}/{key}", f, fuse_laplacian(f.astype(np.float64), L, "mean", "max-abs"))
    # Brovey: include negative values and all-dark pixels (s < 1e-6 branch).
    f = rand(rng, 3, 19, 23, 3) - np.float32(0.15)
    f[:, :4, :5, :] = 0.0
    f[:, 5, 5, :] = np.float32(1e-7)
    case("brovey/19x23x3", f, fuse_brovey(f.astype(np.float64)))
    f = rand(rng, 2, 7, 5, 1)
    case("brovey/7x5x1", f, fuse_brovey(f.astype(np.float64)))
    # Channel-sum: R of frame 1, G of frame 2, B of frame 3.
    f = rand(rng, 3, 9, 7, 3)
    case("channel-sum/9x7x3", f, np.stack([f[0, ..., 0], f[1, ..., 1], f[2, ..., 2]], axis=-1).astype(np.float64))
    write("fusion.bin", records)


# ------------------------------------------------------------- metrics, docs/spec.md
def gradient(y, axis):
    if y.shape[axis] < 2:
        return np.zeros_like(y)  # docs/spec.md: 0 along an axis of length 1
    return np.gradient(y, axis=axis)


def metrics(img, bg):
    y = img[..., 0] if img.shape[-1] == 1 else 0.299 * img[..., 0] + 0.587 * img[..., 1] + 0.114 * img[..., 2]
    gx, gy = gradient(y, 1), gradient(y, 0)
    out = [np.mean(np.sqrt(gx * gx + gy * gy)), np.sqrt(np.mean((y - y.mean()) ** 2))]
    if bg is not None:
        out.append(np.mean(np.abs(img - bg)))
    return np.array(out, dtype=np.float64)


def metrics_vectors(rng):
    records = []
    for shape in [(1, 1, 1), (1, 7, 1), (7, 1, 3), (2, 2, 3), (13, 17, 3), (64, 48, 1), (33, 31, 3)]:
        img, bg = rand(rng, *shape), rand(rng, *shape)
        key = "x".join(str(s) for s in shape)
        records += [(f"{key}/image", img), (f"{key}/background", bg),
                    (f"{key}/metrics", metrics(img.astype(np.float64), bg.astype(np.float64)))]
    bgr = cv2.imread(DIGIT, cv2.IMREAD_UNCHANGED)
    rgb8 = cv2.cvtColor(bgr, cv2.COLOR_BGR2RGB)
    rgb = rgb8.astype(np.float64) / 255.0
    # The background difference of the DIGIT frame against a shifted copy of
    # itself (a stand-in for "touching" frames with real sensor statistics).
    shifted = np.roll(rgb, (3, -2), axis=(0, 1))
    records += [("digit/rgb8", rgb8), ("digit/metrics_vs_shifted", metrics(rgb, shifted))]
    write("metrics.bin", records)


def main():
    os.makedirs(OUT, exist_ok=True)
    print(f"pywt {pywt.__version__}, cv2 {cv2.__version__}, numpy {np.__version__}", file=sys.stderr)
    wavelet_vectors(np.random.default_rng(20240601))
    pyramid_vectors(np.random.default_rng(20240602))
    fusion_vectors(np.random.default_rng(20240603))
    metrics_vectors(np.random.default_rng(20240604))


if __name__ == "__main__":
    main()
