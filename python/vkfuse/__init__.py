"""vkfuse: fuses frames of a vision-based tactile sensor lit under different
LED settings (wavelet, Laplacian pyramid, Brovey, channel sum), on a Vulkan
device or the double-precision CPU reference path, and scores them
(sharpness, RMS contrast, difference from the background).

    import numpy as np, vkfuse
    fused = vkfuse.fuse([white, green])                  # uint8 or float frames, (H, W[, C])
    scores = vkfuse.metrics(fused, background=bg)
    plan = vkfuse.Plan(240, 320, frames=2)               # built once per shape and method
    fused, scores = plan.run([white, green])             # every cycle
    white, green = vkfuse.SimDigit(object="coin").capture([(15, 15, 15), (0, 15, 0)])
    for cycle in vkfuse.Rig(sensors=2).cycles(10): cycle["sensors"][0]["metrics"]
    for f in vkfuse.Dataset("grid").frames("SIM-0001", "coin"): f["pixels"]

Bad arguments and shapes raise ValueError; everything else vkfuse.Error.
"""
from ._vkfuse import Dataset, Error, Plan, Rig, SimDigit, __version__, fuse, metrics

__all__ = ["Dataset", "Error", "Plan", "Rig", "SimDigit", "__version__", "fuse", "metrics"]
