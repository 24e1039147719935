#!/usr/bin/python3
"""Frames as digit-interface hands them out (OpenCV's BGR, transposed and
flipped to portrait 320 x 240) go in unchanged; the fused image comes back
the same way, ready for cv2.imshow or cv2.imwrite.

    python3 examples/python/digit_interface_frames.py
"""
import numpy as np

import vkfuse


def get_frame(landscape_rgb: np.ndarray) -> np.ndarray:
    """What digit_interface.Digit.get_frame() returns for a frame the sensor
    streamed: cv2.transpose then cv2.flip(frame, 0), in BGR."""
    return np.ascontiguousarray(np.flip(np.swapaxes(landscape_rgb[..., ::-1], 0, 1), 0))


sim = vkfuse.SimDigit(object="screw")
white, green = (get_frame(f) for f in sim.capture([(15, 15, 15), (0, 15, 0)]))
assert white.shape == (320, 240, 3)

plan = vkfuse.Plan(320, 240, frames=2, channel_order="bgr", layout="digit-interface", out_dtype=np.uint8)
fused, scores = plan.run([white, green])
assert fused.shape == (320, 240, 3) and fused.dtype == np.uint8
same = vkfuse.metrics(white, channel_order="bgr", layout="digit-interface")
print(f"fused a portrait BGR pair on {plan.backend}: sharpness {scores['sharpness']:.5f} "
      f"(white frame alone {same['sharpness']:.5f})")
