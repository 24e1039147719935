#!/usr/bin/python3
"""What the Python module adds to a cycle: vkfuse.Plan.run against the C++
Plan::run that vkfuse-bench times, for the same cell (QVGA, K = 3, S = 1,
wavelet bior4.4, float32 frames, fused image and all three metrics read back),
in one run on an idle host.

    PYTHONPATH=build/python python3 bench/python_overhead.py build/bench/vkfuse-bench [--backend vulkan]

Prints one JSON object {"cpp_median_ms", "python_median_ms", "ratio", ...};
exit status 1 when the ratio exceeds 1.10 (issue 16's bound), 2 on bad usage.
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile
import time

import numpy as np

import vkfuse

H, W, K = 240, 320, 3


def bench_cell(bench, backend, runs):
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "cell.json")
        subprocess.run([bench, "--method", "wavelet", "--wavelet", "bior4.4", "--size", f"{W}x{H}",
                        "--frames", str(K), "--sensors", "1", "--backend", backend, "--no-peers",
                        "--runs", str(runs), "--json", out], check=True, stdout=subprocess.DEVNULL)
        with open(out) as f:
            cells = json.load(f)
    return cells[0]


def python_cycle_ms(backend, runs):
    plan = vkfuse.Plan(H, W, channels=3, frames=K, dtype="float32",
                       metrics=["sharpness", "contrast", "background_diff"], backend=backend)
    rng = np.random.default_rng(1)
    plan.set_background(rng.random((H, W, 3), np.float32))
    frames = [rng.random((H, W, 3), np.float32) for _ in range(K)]
    plan.run(frames)  # warm-up
    times = []
    for _ in range(runs):
        start = time.perf_counter()
        plan.run(frames)
        times.append((time.perf_counter() - start) * 1e3)
    return float(np.median(times)), plan.backend


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("bench", help="the vkfuse-bench program")
    p.add_argument("--backend", default="vulkan", choices=["vulkan", "cpu"])
    p.add_argument("--runs", type=int, default=50)
    args = p.parse_args()
    cell = bench_cell(args.bench, args.backend, args.runs)
    python_ms, backend = python_cycle_ms(args.backend, args.runs)
    ratio = python_ms / cell["median_ms"]
    print(json.dumps({"cell": f"wavelet bior4.4 {W}x{H} K={K} S=1 {backend}", "device": cell["device"],
                      "cpp_median_ms": cell["median_ms"], "python_median_ms": python_ms, "ratio": ratio}))
    return 1 if ratio > 1.10 else 0


if __name__ == "__main__":
    sys.exit(main())
