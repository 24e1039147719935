#!/usr/bin/env python3
"""Makes the quick-start demo frames from the real DIGIT background.

The real DIGIT frame (tests/data/digit_bg_tacto.png) was captured with all
three LEDs at 15. Until the simulated DIGIT lands, the demo imitates the
paper's best pair, (15,15,15) + (0,15,0), by relighting that frame: the
green-only frame keeps the green channel, keeps 12 % of red and blue (camera
crosstalk) and adds a pressed "coin" whose relief only the grazing green light
shows. Deterministic; needs python3-numpy and python3-opencv.
"""
import cv2
import numpy as np

rgb = cv2.imread("tests/data/digit_bg_tacto.png")[..., ::-1].astype(np.float64) / 255.0
h, w, _ = rgb.shape
y, x = np.mgrid[0:h, 0:w]
r = np.hypot(x - w * 0.5, y - h * 0.55)
relief = np.where(r < 60, 0.5 + 0.5 * np.cos(r / 6.0) * np.cos((x - y) / 9.0), 0.0)
gy, gx = np.gradient(relief)
white = np.clip(rgb + 0.05 * (gx + gy)[..., None], 0, 1)
green = rgb * np.array([0.12, 1.0, 0.12])
green[..., 1] += 0.25 * gx - 0.1 * gy
rng = np.random.default_rng(7)
for name, img in (("demo_white.png", white), ("demo_green.png", green)):
    img = np.clip(img + rng.normal(0, 0.004, img.shape), 0, 1)
    cv2.imwrite("tests/data/" + name, np.round(img * 255).astype(np.uint8)[..., ::-1])
