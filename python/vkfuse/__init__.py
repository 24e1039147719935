"""vkfuse: fuses frames of a vision-based tactile sensor lit under different
LED settings (wavelet, Laplacian pyramid, Brovey, channel sum), on a Vulkan
device or the double-precision CPU reference path, and scores them
(sharpness, RMS contrast, difference from the background).

numpy:
    fused = vkfuse.fuse(np.stack([white, green]))          # (K, H, W, C) or a list; uint8/16, float32/64
    fused = vkfuse.fuse(frames, out_dtype=np.uint8)          # clamped to [0, 1], x 255, rounded
    scores = vkfuse.metrics(fused, background=bg)
    plan = vkfuse.Plan(240, 320, frames=2, sensors=8)       # built once; run() every cycle
    fused, scores = plan.run(batch)                          # (S, K, H, W, C) -> (S, H, W, C), one submit
PyTorch:
    fused = vkfuse.fuse(torch.stack([a, b]))                 # a torch.Tensor back, sharing memory
digit-interface / OpenCV (BGR, portrait 320 x 240):
    fused = vkfuse.fuse([digit.get_frame(), ...], channel_order="bgr", layout="digit-interface")
The rig of `vkfuse run`:
    with vkfuse.Rig(sensors=2, virtual_clock=True) as rig:
        for cycle in rig.cycles(10): cycle["sensors"][0]["metrics"]

Bad arguments raise ValueError or TypeError naming the argument; anything
else the library refuses raises vkfuse.Error.
"""
from ._vkfuse import DeviceTensor, Error, SimDigit, __version__
from ._fusion import fuse, metrics
from ._plan import Plan
from ._rig import Dataset, Rig

__all__ = ["Dataset", "DeviceTensor", "Error", "Plan", "Rig", "SimDigit", "__version__", "fuse", "metrics"]
