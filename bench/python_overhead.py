#!/usr/bin/python3
"""What the Python module adds to a cycle, and what a batch saves.

1. plan.run from Python against Plan::run timed in C++ (Plan.cpp_cycle_ms),
   the same plan and frames, in alternating rounds in one process so that
   both see the same host (QVGA, K = 3, S = 1, wavelet bior4.4, float32
   frames, fused image and all three metrics). Bound: at most 1.10x.
2. A batch of S = 8 sensors in one plan.run (one submit, (8, K, H, W, 3)
   uint8 as a camera gives them) against eight single-sensor plan.run calls:
   ms per sensor-cycle, alternating rounds. Bound: the batch at most 1.0x.

    PYTHONPATH=build/python python3 bench/python_overhead.py [--rounds 10] [--runs 20]

Prints one JSON object per measurement; exit status 1 when a bound is
exceeded, 2 on bad usage.
"""
import argparse
import json
import sys
import time

import numpy as np

import vkfuse

H, W, K = 240, 320, 3


def python_median_ms(plan, frames, runs):
    times = []
    for _ in range(runs):
        start = time.perf_counter()
        plan.run(frames)
        times.append((time.perf_counter() - start) * 1e3)
    return float(np.median(times))


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--rounds", type=int, default=10)
    p.add_argument("--runs", type=int, default=20)
    args = p.parse_args()
    plan = vkfuse.Plan(H, W, channels=3, frames=K, dtype="float32",
                       metrics=["sharpness", "contrast", "background_diff"], backend="vulkan")
    rng = np.random.default_rng(1)
    plan.set_background(rng.random((H, W, 3), np.float32))
    frames = [rng.random((H, W, 3), np.float32) for _ in range(K)]
    plan.run(frames)  # warm-up
    cpp, python = [], []
    for _ in range(args.rounds):
        cpp.append(plan.cpp_cycle_ms(frames, args.runs))
        python.append(python_median_ms(plan, frames, args.runs))
    cpp_ms, python_ms = float(np.median(cpp)), float(np.median(python))
    ratio = python_ms / cpp_ms
    print(json.dumps({"cell": f"wavelet bior4.4 {W}x{H} K={K} S=1", "rounds": args.rounds, "runs": args.runs,
                      "cpp_median_ms": cpp_ms, "python_median_ms": python_ms, "ratio": ratio,
                      "round_ratios": [round(p / c, 3) for p, c in zip(python, cpp)]}))
    batch_ratio = batch_against_singles(rng, args.rounds, max(2, args.runs // 4))
    return 1 if ratio > 1.10 or batch_ratio > 1.0 else 0


def batch_against_singles(rng, rounds, runs, sensors=8):
    batch = rng.integers(0, 256, (sensors, K, H, W, 3), dtype=np.uint8)
    together = vkfuse.Plan(H, W, frames=K, sensors=sensors, metrics=["sharpness", "contrast"], backend="vulkan")
    alone = vkfuse.Plan(H, W, frames=K, metrics=["sharpness", "contrast"], backend="vulkan")
    together.run(batch)
    alone.run(batch[0])
    per_sensor_batch, per_sensor_single = [], []
    for _ in range(rounds):
        per_sensor_batch.append(python_median_ms(together, batch, runs) / sensors)
        times = []
        for _ in range(runs):
            start = time.perf_counter()
            for s in range(sensors):
                alone.run(batch[s])
            times.append((time.perf_counter() - start) * 1e3 / sensors)
        per_sensor_single.append(float(np.median(times)))
    b, s = float(np.median(per_sensor_batch)), float(np.median(per_sensor_single))
    print(json.dumps({"cell": f"wavelet bior4.4 {W}x{H} K={K} uint8, S={sensors} in one run against {sensors} runs",
                      "rounds": rounds, "runs": runs, "batch_ms_per_sensor": b, "single_ms_per_sensor": s,
                      "ratio": b / s}))
    return b / s


if __name__ == "__main__":
    sys.exit(main())
