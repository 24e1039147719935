"""vkfuse.Rig from Python on an emulated DIGIT, inside the HIL virtual
machine (tests/hil/in_vm.sh): a real DIGIT opened by serial through V4L2 and
its LED protocol, frames handed back as digit-interface hands them out (BGR,
portrait), each cycle fused as vkfuse.fuse() fuses those frames.

    python3 rig_from_python.py SERIAL
"""
import sys

import numpy as np

import vkfuse

serial = sys.argv[1]
with vkfuse.Rig(sensor=serial, backend="cpu", method="brovey", background_frames=2, skip="off",
                sequence=[(15, 15, 15), (0, 15, 0)], channel_order="bgr", layout="digit-interface") as rig:
    assert rig.sensors == [serial], rig.sensors
    cycles = list(rig.cycles(5))
assert len(cycles) == 5, len(cycles)
for cycle in cycles:
    (s,) = cycle["sensors"]
    assert s["serial"] == serial and s["status"] == "ok", (s["status"], s["error"])
    white, green = s["frames"]
    assert white.shape == (320, 240, 3) and white.dtype == np.uint8, white.shape
    assert s["fused"].shape == (320, 240, 3)
    want = vkfuse.fuse(s["frames"], method="brovey", channel_order="bgr", layout="digit-interface", backend="cpu")
    assert np.max(np.abs(s["fused"] - want)) <= 1e-6
    b, g, r = (float(green[..., c].mean()) for c in range(3))
    assert g > r and g > b, f"the green-lit frame's BGR means: {b:.1f} {g:.1f} {r:.1f}"
m = cycles[-1]["sensors"][0]["metrics"]
print(f"hil: python: 5 cycles of {serial} by serial, portrait BGR frames, fused as vkfuse.fuse fuses them; "
      f"sharpness {m['sharpness']:.5f}, background_diff {m['background_diff']:.5f}")
