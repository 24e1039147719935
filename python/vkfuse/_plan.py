"""vkfuse.Plan: built once for a shape, K, S and method; run every cycle."""
from __future__ import annotations

from typing import Any, List, Optional, Sequence, Tuple

import numpy as np

from . import _vkfuse
from ._arrays import Layout, engine_frames, engine_out, finish
from ._conventions import INPUT_DTYPES, UNSET, dtype_name, spec_kwargs

# A dict of metrics, or for a batch a list of them (one per sensor).
Scores = Any


class Plan:
    """Everything for one shape, K frames per cycle, S sensors and method is
    made once (on the Vulkan device when there is one, else the CPU
    reference path with the same interface); run() fuses a cycle.

    height, width: one frame's size as the caller holds it (digit-interface's
        portrait frames: Plan(320, 240, layout="digit-interface")).
    channels: 1 or 3.  frames: K, the frames fused per sensor per cycle.
    dtype: the frames' dtype: uint8, uint16, float32 or float64 (a numpy
        dtype or its name).
    method, wavelet, levels, level, mode, base_rule, detail_rule, backend,
    channel_order, layout, out_dtype, clamp: as vkfuse.fuse().
    metrics: the metrics each run() returns: sharpness, contrast,
        background_diff (needs set_background()); () for none.
    sensors: S, the sensors one run() fuses in one submit.
    on_device: run() leaves the fused images in device memory that can be
        shared and returns a vkfuse.DeviceTensor (DLPack on kDLVulkan, an
        opaque fd for CUDA or another process; README, "Python"); needs the
        Vulkan backend and the engine's own layout (landscape RGB float32).

    A Plan is one thread's at a time: run() from two threads at once is
    serialised (each waits its turn with the GIL released); different
    plans run in parallel.
    """

    def __init__(self, height: int, width: int, channels: int = 3, frames: int = 2, dtype: Any = "uint8",
                 method: str = "wavelet", wavelet: Any = "bior4.4", levels: Optional[int] = None,
                 mode: str = "periodization", base_rule: str = "mean", detail_rule: str = "max-abs",
                 metrics: Sequence[str] = ("sharpness", "contrast"), backend: str = "auto", *, sensors: int = 1,
                 level: Any = UNSET, channel_order: str = "rgb", layout: str = "landscape", out_dtype: Any = None,
                 clamp: Optional[bool] = None, on_device: bool = False) -> None:
        for name, value in (("height", height), ("width", width), ("channels", channels), ("frames", frames),
                            ("sensors", sensors)):
            if isinstance(value, bool) or not isinstance(value, int):
                raise TypeError(f"{name}: {type(value).__name__}; expected an int")
        if isinstance(metrics, str):
            raise TypeError("metrics: a str; expected a sequence of names, e.g. ('sharpness', 'contrast')")
        self._layout = Layout.of(channel_order, layout)
        self._dtype = dtype_name(dtype, "dtype", INPUT_DTYPES)
        self._height, self._width, self._channels = height, width, channels
        self._out_dtype, self._clamp = out_dtype, clamp
        h, w = self._layout.engine_size(height, width)
        spec = spec_kwargs(method, wavelet, levels, level, mode, base_rule, detail_rule, h, w)
        engine_dtype = "uint8" if self._dtype == "uint8" else "float32"
        if on_device and (self._layout != Layout() or out_dtype not in (None, "float32", np.float32) or clamp):
            raise ValueError("on_device: the images stay as the engine writes them: landscape RGB float32, "
                             "unclamped (no channel_order, layout, out_dtype or clamp)")
        self._on_device = bool(on_device)
        self._plan = _vkfuse.Plan(h, w, channels, frames, sensors=sensors, dtype=engine_dtype,
                                  metrics=list(metrics), backend=backend, on_device=self._on_device, **spec)

    @property
    def backend(self) -> str:
        """"vulkan" or "cpu": where this plan runs."""
        return self._plan.backend

    @property
    def sensors(self) -> int:
        return self._plan.sensors

    def _engine(self, frames: Any, name: str = "frames") -> Tuple[Any, List[Any]]:
        frame_ndim = 3
        if self._channels == 1:  # gray frames are (H, W) or (H, W, 1): told apart by their last axes
            shape = getattr(frames, "shape", None)
            frame_ndim = 2 if shape is not None and tuple(shape[-2:]) == (self._height, self._width) else 3
        given = engine_frames(frames, name, self._layout, frame_ndim=frame_ndim)
        if given.dtype != self._dtype and {given.dtype, self._dtype} != {"float32", "float64"}:
            raise ValueError(f"{name}: dtype {given.dtype}; the plan takes {self._dtype}")
        if given.sensors != self.sensors or (self.sensors > 1 and not given.batched):
            raise ValueError(f"{name}: {given.sensors} sensor(s) given; the plan fuses {self.sensors} "
                             "(a batch (S, K, H, W[, C]) or S lists of K frames)")
        return given, given.frames

    def set_background(self, background: Any, sensor: int = 0) -> None:
        """The background image of one sensor (for background_diff), in the frames' dtype and layout."""
        one = engine_frames(background, "background", self._layout, single=True)
        self._plan.set_background(one.frames[0], sensor)

    def run(self, frames: Any, out: Any = None, like: Any = None) -> Tuple[Any, Scores]:
        """Fuses one cycle: (fused image, metrics dict). frames as vkfuse.fuse()
        takes them; with sensors > 1 (or frames given as a batch) the image is
        (S, H, W[, C]) and the metrics a list of dicts, one per sensor. out,
        like: as vkfuse.fuse(). Releases the GIL while the plan runs."""
        given, engine = self._engine(frames)
        if self._on_device:
            tensor, scores = self._plan.run(engine, out=out)
            return tensor, (scores if given.batched else scores[0])
        shape = (self.sensors,) + engine[0].shape
        direct = engine_out(out, given, self._layout, self._out_dtype, self._clamp, shape)
        fused, scores = self._plan.run(engine, out=direct)
        result = out if direct is not None else finish(fused, given, self._layout, self._out_dtype, self._clamp,
                                                       out, like)
        return result, (scores if given.batched else scores[0])

    def cpp_cycle_ms(self, frames: Any, runs: int = 20) -> float:
        """The median ms of the C++ Plan::run alone on these frames (what run()'s overhead is measured against)."""
        return self._plan.cpp_cycle_ms(self._engine(frames)[1], runs)
