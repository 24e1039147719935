#!/usr/bin/python3
"""The paper-style Python pipelines vkfuse-bench compares against.

One sensor cycle, as a Python tactile pipeline does it: fuse the K frames with
PyWavelets (wavedec2/waverec2), OpenCV (pyrDown/pyrUp) or numpy, then the three
metrics with numpy (np.gradient sharpness, RMS contrast, background difference).
The bench writes the frames as float32 .npy files and runs:

    pipelines.py --method wavelet --wavelet bior4.4 --levels 3 --runs 20 \
        --max-seconds 60 --background bg.npy --out fused.npy f0.npy f1.npy f2.npy

The script times its own loop (one untimed warm-up, then at least 5 timed runs;
more up to --runs while they fit --max-seconds), prints one JSON object
{"peer", "median_ms", "min_ms", "max_ms", "runs", "sharpness", "contrast",
"background_diff"} and writes the fused image of the last run to --out.

The frames stay float32, as a pipeline reading camera frames would keep them:
the libraries then compute in float32, so the peer is as fast as it can be
(the bench measures its error against vkfuse's double reference).
docs/spec.md's rules: base "mean", detail "max-abs" (ties to the lowest frame).
Exit status 2 with a one-line message on bad arguments or missing libraries.
"""
import argparse
import json
import sys
import time

try:
    import numpy as np
except ImportError as e:  # pragma: no cover - reported to the bench as one line
    print(f"pipelines.py: {e}", file=sys.stderr)
    sys.exit(2)

MIN_RUNS = 5


def max_abs(stack):
    """Coefficient of largest magnitude across frames (axis 0); argmax takes
    the first maximum, so ties go to the lowest frame index."""
    idx = np.argmax(np.abs(stack), axis=0)
    return np.take_along_axis(stack, idx[None], axis=0)[0]


def base_mean(stack):
    return np.mean(stack, axis=0)


def channel_sum(frames):
    return np.stack([frames[0][..., 0], frames[1][..., 1], frames[2][..., 2]], axis=-1)


def brovey(frames):
    stack = np.stack(frames)
    p = np.maximum(stack, 0)
    s = p.sum(axis=0)
    safe = np.where(s >= 1e-6, s, 1)
    return np.where(s >= 1e-6, (p / safe * stack).sum(axis=0), stack.mean(axis=0))


def laplacian(frames, levels):
    import cv2

    def pyramid(g):
        out = []
        for _ in range(levels):
            nxt = cv2.pyrDown(g)
            out.append(g - cv2.pyrUp(nxt, dstsize=(g.shape[1], g.shape[0])))
            g = nxt
        return out + [g]

    pyrs = [pyramid(f) for f in frames]
    fused = [max_abs(np.stack([p[l] for p in pyrs])) for l in range(levels)]
    fused.append(base_mean(np.stack([p[levels] for p in pyrs])))
    r = fused[levels]
    for l in range(levels - 1, -1, -1):
        r = cv2.pyrUp(r, dstsize=(fused[l].shape[1], fused[l].shape[0])) + fused[l]
    return r


def wavelet(frames, family, levels):
    import pywt

    coeffs = [pywt.wavedec2(f, family, mode="periodization", level=levels, axes=(0, 1)) for f in frames]
    fused = [base_mean(np.stack([c[0] for c in coeffs]))]
    for l in range(1, levels + 1):
        fused.append(tuple(max_abs(np.stack([c[l][b] for c in coeffs])) for b in range(3)))
    h, w = frames[0].shape[:2]
    return pywt.waverec2(fused, family, mode="periodization", axes=(0, 1))[:h, :w]


def metrics(img, background):
    y = 0.299 * img[..., 0] + 0.587 * img[..., 1] + 0.114 * img[..., 2]
    gy, gx = np.gradient(y)
    return (float(np.mean(np.sqrt(gx * gx + gy * gy))), float(np.std(y)),
            float(np.mean(np.abs(img - background))))


def peer_name(method):
    names = [f"numpy {np.__version__}"]
    if method == "laplacian":
        import cv2
        names.insert(0, f"opencv-python {cv2.__version__} pyrDown/pyrUp")
    if method == "wavelet":
        import pywt
        names.insert(0, f"pywt {pywt.__version__} wavedec2/waverec2")
    return " + ".join(names)


def pipeline(args):
    if args.method == "channel-sum":
        return channel_sum
    if args.method == "brovey":
        return brovey
    if args.method == "laplacian":
        return lambda frames: laplacian(frames, args.levels)
    return lambda frames: wavelet(frames, args.wavelet, args.levels)


def parse_args():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--method", required=True, choices=["channel-sum", "brovey", "laplacian", "wavelet"])
    p.add_argument("--wavelet", default="bior4.4", choices=["haar", "db2", "bior2.2", "bior4.4"])
    p.add_argument("--levels", type=int, default=0)
    p.add_argument("--runs", type=int, default=20)
    p.add_argument("--max-seconds", type=float, default=60.0)
    p.add_argument("--background", required=True)
    p.add_argument("--out", required=True)
    p.add_argument("frames", nargs="+")
    args = p.parse_args()
    if args.levels <= 0:
        args.levels = 4 if args.method == "laplacian" else 3
    return args


def main():
    args = parse_args()
    try:
        fuse = pipeline(args)
        name = peer_name(args.method)
        frames = [np.load(f) for f in args.frames]
        background = np.load(args.background)
    except (ImportError, OSError, ValueError) as e:
        print(f"pipelines.py: {e}", file=sys.stderr)
        sys.exit(2)

    def cycle():
        fused = fuse(frames)
        return fused, metrics(fused, background)

    times = []
    start = time.perf_counter()
    cycle()  # warm-up: imports, allocator, caches
    first = time.perf_counter() - start
    runs = max(MIN_RUNS, min(args.runs, int(args.max_seconds / max(first, 1e-9))))
    for _ in range(runs):
        start = time.perf_counter()
        fused, m = cycle()
        times.append((time.perf_counter() - start) * 1e3)
    np.save(args.out, np.ascontiguousarray(fused, dtype=np.float32))
    print(json.dumps({"peer": name, "median_ms": float(np.median(times)), "min_ms": min(times),
                      "max_ms": max(times), "runs": len(times), "sharpness": m[0], "contrast": m[1],
                      "background_diff": m[2]}))


if __name__ == "__main__":
    main()
