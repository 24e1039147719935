#!/usr/bin/python3
"""A PyTorch user's habits: a batch of sensors as one tensor in, tensors out,
the fused images written into a preallocated tensor, 8-bit output clamped.

    python3 examples/python/torch_batch.py
"""
import numpy as np
import torch

import vkfuse

S, K, H, W = 4, 2, 240, 320
sim = vkfuse.SimDigit(object="coin")
cycle = [np.stack(sim.capture([(15, 15, 15), (0, 15, 0)])) for _ in range(S)]
batch = torch.from_numpy(np.stack(cycle))  # (S, K, H, W, 3) uint8, as a DataLoader would stack it

plan = vkfuse.Plan(H, W, frames=K, sensors=S, dtype=np.uint8)
fused, scores = plan.run(batch)  # one submit for all S sensors
assert isinstance(fused, torch.Tensor) and tuple(fused.shape) == (S, H, W, 3)

into = torch.empty((S, H, W, 3), dtype=torch.float32)
plan.run(batch, out=into)  # no new array: the plan fills the caller's tensor
assert torch.equal(into, fused)

as_uint8 = vkfuse.fuse(batch, out_dtype=np.uint8)  # clamped to [0, 1], x 255, rounded: never wrapped
print(f"fused {S} sensors on {plan.backend}: sharpness {[round(s['sharpness'], 5) for s in scores]}, "
      f"8-bit range {int(as_uint8.min())}..{int(as_uint8.max())}")
