#!/usr/bin/python3
"""Fuses a DIGIT-like pair with the installed Python module: the gel lit
white (15,15,15) and green (0,15,0), the paper's best pair, with its best
method (wavelet, bior4.4, 3 levels); prints the metrics and whether the
device's image agrees with the CPU reference.

    PYTHONPATH=P/lib/python3/dist-packages python3 examples/python/fuse_pair.py
"""
import numpy as np

import vkfuse

H, W = 240, 320
y, x = np.mgrid[0:H, 0:W]
# A coin pressed into the gel: a disc whose rim catches the light, over smooth shading.
r = np.hypot(x - 170, y - 115)
relief = np.exp(-((r - 40) / 6.0) ** 2) + 0.3 * (r < 40)
shade = 0.35 + 0.25 * np.cos(x / W * np.pi - 0.5)
texture = 0.02 * np.random.default_rng(7).standard_normal((H, W))
white = np.clip(np.stack([shade + 0.5 * relief + texture] * 3, axis=-1) * [0.95, 1.0, 0.9], 0, 1)
green = np.clip(np.stack([0.1 * shade, shade + 0.8 * relief + texture, 0.3 * shade], axis=-1), 0, 1)
frames = [np.round(f * 255).astype(np.uint8) for f in (white, green)]  # as a camera delivers them

plan = vkfuse.Plan(H, W, channels=3, frames=2, dtype="uint8")
fused, metrics = plan.run(frames)
reference = vkfuse.fuse(frames, backend="cpu")
err = float(np.max(np.abs(fused - reference)))
print(f"vkfuse {vkfuse.__version__}: fused {H}x{W}x3 on {plan.backend}; "
      f"sharpness {metrics['sharpness']:.5f}, contrast {metrics['contrast']:.5f}")
if plan.backend == "cpu":
    print("CPU reference only (no usable Vulkan device)")
elif err <= 1e-5:
    print(f"the device and the CPU reference agree (max |difference| {err:.2e})")
else:
    raise SystemExit(f"the device's image differs from the CPU reference by {err:.2e}")
