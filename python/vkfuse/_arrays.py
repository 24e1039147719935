"""Arrays as users hold them, in and out of the engine.

In: a list of frames, a stacked (K, H, W[, C]) array or a batch
(S, K, H, W[, C]); numpy arrays, torch CPU tensors or anything with
__dlpack__ or the array interface; uint8, uint16, float32 or float64; any
strides; RGB or BGR; landscape (the sensor's) or digit-interface's portrait.
The engine reads C-ordered landscape RGB frames: a frame already so is
handed over as it is (the same memory), any other is copied once.

Out: the engine's float32 (S, H, W[, C]) landscape RGB, turned back into the
caller's layout and channel order (views), dtype and array type, or written
into the caller's `out`.
"""
from __future__ import annotations

import sys
from dataclasses import dataclass
from typing import Any, List, Optional, Sequence, Tuple

import numpy as np

from ._conventions import INPUT_DTYPES, OUTPUT_DTYPES, dtype_name

LAYOUTS = ("landscape", "digit-interface")
CHANNEL_ORDERS = ("rgb", "bgr")
# DLPack device types whose memory the host reads directly.
_HOST_DEVICES = {1: "cpu", 3: "cuda-host", 11: "rocm-host", 13: "cuda-managed"}
_SCALE = {"uint8": 255.0, "uint16": 65535.0}


@dataclass(frozen=True)
class Layout:
    """How the caller holds images: channel order and orientation."""

    channel_order: str = "rgb"
    layout: str = "landscape"

    @staticmethod
    def of(channel_order: Any = "rgb", layout: Any = "landscape") -> "Layout":
        if channel_order not in CHANNEL_ORDERS:
            raise ValueError(f"channel_order {channel_order!r}: expected 'rgb' or 'bgr'")
        if layout not in LAYOUTS:
            raise ValueError(f"layout {layout!r}: expected 'landscape' or 'digit-interface' (portrait, as "
                             "digit-interface's get_frame() returns it)")
        return Layout(channel_order, layout)

    @property
    def portrait(self) -> bool:
        return self.layout == "digit-interface"

    def engine_size(self, height: int, width: int) -> Tuple[int, int]:
        """The engine's (height, width) of a caller's height x width image."""
        return (width, height) if self.portrait else (height, width)

    def to_engine(self, frame: np.ndarray) -> np.ndarray:
        """A caller's (H, W[, C]) frame as the engine's landscape RGB (a view).
        digit-interface's portrait(i, j) = landscape(j, W - 1 - i)."""
        if self.portrait:
            frame = np.rot90(frame, -1)
        if self.channel_order == "bgr" and frame.ndim == 3 and frame.shape[2] == 3:
            frame = frame[..., ::-1]
        return frame

    def to_caller(self, images: np.ndarray, first_image_axis: int) -> np.ndarray:
        """The engine's images (H, W[, C]) from axis first_image_axis on, in the caller's layout (a view)."""
        colour = images.ndim - first_image_axis == 3
        if self.channel_order == "bgr" and colour and images.shape[-1] == 3:
            images = images[..., ::-1]
        if self.portrait:
            images = np.rot90(images, 1, axes=(first_image_axis, first_image_axis + 1))
        return images


def as_array(x: Any, name: str) -> np.ndarray:
    """x as a numpy array over the same memory where it has one on the host."""
    if isinstance(x, np.ndarray):
        return x
    if hasattr(x, "__dlpack_device__"):
        device = x.__dlpack_device__()
        kind = int(device[0])
        if kind not in _HOST_DEVICES:
            raise TypeError(f"{name}: a tensor in device memory (DLPack device type {kind}); vkfuse reads host "
                            "memory: move it first (tensor.cpu())")
        try:
            return np.from_dlpack(x)
        except (BufferError, RuntimeError, TypeError) as e:
            raise TypeError(f"{name}: cannot be read through DLPack ({str(e).splitlines()[0]})") from None
    if hasattr(x, "__array_interface__") or hasattr(x, "__array_struct__") or hasattr(x, "__array__"):
        return np.asarray(x)
    raise TypeError(f"{name}: {type(x).__name__} is not an array (expected a numpy array, a tensor or an object "
                    "with __dlpack__ or the array interface)")


def _is_sequence(x: Any) -> bool:
    return isinstance(x, (list, tuple))


@dataclass
class EngineFrames:
    """S x K frames, sensor-major, as the engine reads them, and how to answer."""

    frames: List[np.ndarray]
    sensors: int
    batched: bool          # given as a batch: results keep the sensor axis
    dtype: str             # the caller's dtype
    shape: Tuple[int, ...]  # one caller frame's shape
    like: Any              # the first input that was not a numpy array (e.g. a torch tensor), else None


def _frame_lists(frames: Any, name: str, frame_ndim: Optional[int],
                 single: bool) -> Tuple[List[List[Tuple[str, np.ndarray]]], bool, Any]:
    """frames as S lists of K (name, array) and whether it was a batch.
    frame_ndim: the dimensions of one frame where known (a plan's), else
    a stacked array of 3 dimensions is (K, H, W) and of 4 (K, H, W, C).
    single: frames is one frame, named `name`."""
    like = None if single or isinstance(frames, np.ndarray) or _is_sequence(frames) else frames
    if single:
        return [[(name, as_array(frames, name))]], False, None

    def array(x: Any, label: str) -> np.ndarray:
        nonlocal like
        if like is None and not isinstance(x, np.ndarray) and not _is_sequence(x):
            like = x
        return as_array(x, label)

    def stack(a: np.ndarray, label: str) -> List[Tuple[str, np.ndarray]]:
        return [(f"{label}[{k}]", a[k]) for k in range(a.shape[0])]

    if _is_sequence(frames):
        if len(frames) == 0:
            raise ValueError(f"{name}: no frames given")
        if all(_is_sequence(f) for f in frames):
            return [[(f"{name}[{s}][{k}]", array(x, f"{name}[{s}][{k}]")) for k, x in enumerate(group)]
                    for s, group in enumerate(frames)], True, like
        arrays = [array(x, f"{name}[{k}]") for k, x in enumerate(frames)]
        per_frame = frame_ndim if frame_ndim is not None else 3
        if all(a.ndim == per_frame + 1 for a in arrays) and (frame_ndim is not None or all(a.ndim == 4 for a in arrays)):
            return [stack(a, f"{name}[{s}]") for s, a in enumerate(arrays)], True, like
        return [[(f"{name}[{k}]", a) for k, a in enumerate(arrays)]], False, like
    a = array(frames, name)
    if frame_ndim is None:
        if a.ndim == 3 and a.shape[-1] <= 4:
            raise ValueError(f"{name}: shape {a.shape} reads as one (H, W, C) image; give K frames as a list, "
                             "(K, H, W) gray or (K, H, W, C) (a gray stack this narrow as (K, H, W, 1))")
        frame_ndim = 2 if a.ndim == 3 else 3
    if a.ndim == frame_ndim + 1:
        return [stack(a, name)], False, like
    if a.ndim == frame_ndim + 2:
        return [stack(a[s], f"{name}[{s}]") for s in range(a.shape[0])], True, like
    raise ValueError(f"{name}: {a.ndim} dimensions; expected a list of frames, a stack (K, H, W[, C]) or a batch "
                     "(S, K, H, W[, C])")


def engine_frames(frames: Any, name: str, layout: Layout, frame_ndim: Optional[int] = None,
                  single: bool = False) -> EngineFrames:
    """Checks frames and makes each one the engine's (copied only where it is
    not already C-ordered landscape RGB uint8, float32 or float64)."""
    groups, batched, like = _frame_lists(frames, name, frame_ndim, single)
    k = len(groups[0])
    if k == 0:
        raise ValueError(f"{name}: no frames given")
    first_name, first = groups[0][0]
    out: List[np.ndarray] = []
    for s, group in enumerate(groups):
        if len(group) != k:
            raise ValueError(f"{name}[{s}]: {len(group)} frames; {name}[0] has {k}")
        for label, a in group:
            if a.dtype.name not in INPUT_DTYPES:
                raise ValueError(f"{label}: dtype {a.dtype.name}; expected {', '.join(INPUT_DTYPES)}")
            if a.ndim not in (2, 3):
                raise ValueError(f"{label}: {a.ndim} dimensions; a frame is (H, W) or (H, W, C)")
            if a.shape != first.shape:
                raise ValueError(f"{label}: shape {a.shape}; {first_name} is {first.shape}")
            if a.dtype != first.dtype:
                raise ValueError(f"{label}: dtype {a.dtype.name}; {first_name} is {first.dtype.name}")
            if a.ndim == 3 and a.shape[2] not in (1, 3):
                raise ValueError(f"{label}: {a.shape[2]} channels; expected 1 or 3")
            if min(a.shape[:2]) < 1 or max(a.shape[:2]) > 65536:
                raise ValueError(f"{label}: shape {a.shape}; expected H, W in 1..65536")
            view = layout.to_engine(a)
            if a.dtype == np.uint16:
                view = view / 65535.0  # float64: the command line's v / 65535, exactly
            out.append(np.ascontiguousarray(view))
    return EngineFrames(out, len(groups), batched, first.dtype.name, tuple(first.shape), like)


def output_dtype(out_dtype: Any, out: Optional[np.ndarray]) -> str:
    if out_dtype is None:
        return out.dtype.name if out is not None else "float32"
    return dtype_name(out_dtype, "out_dtype", OUTPUT_DTYPES)


def writable(out: Any) -> np.ndarray:
    """The caller's `out` as a writeable numpy array over its memory."""
    if isinstance(out, np.ndarray):
        a = out
    elif hasattr(out, "numpy") and hasattr(out, "__dlpack__"):  # a torch CPU tensor: .numpy() shares it, writeable
        try:
            a = out.numpy()
        except (RuntimeError, TypeError) as e:
            raise TypeError(f"out: cannot be written in place ({str(e).splitlines()[0]})") from None
    else:
        a = as_array(out, "out")
    if not a.flags.writeable:
        raise ValueError("out: read-only")
    return a


def finish(fused: np.ndarray, frames: EngineFrames, layout: Layout, out_dtype: Any, clamp: Optional[bool],
           out: Any, like: Any) -> Any:
    """The engine's float32 (S, H, W[, C]) as the caller asked for it:
    layout and channel order, dtype (clamped for integers), out= or a new
    array of `like`'s kind (a torch tensor for a torch input)."""
    images = fused if frames.batched else fused[0]
    result = layout.to_caller(images, 1 if frames.batched else 0)
    target = writable(out) if out is not None else None
    dtype = output_dtype(out_dtype, target)
    integer = dtype in _SCALE
    if clamp is None:
        clamp = integer
    elif not clamp and integer:
        raise ValueError(f"clamp=False: {dtype} output holds [0, 1] only; clamp it or ask for a float dtype")
    if clamp:
        np.clip(result, 0.0, 1.0, out=result)
    if integer:
        result = result * _SCALE[dtype]
        np.rint(result, out=result)
    if target is not None:
        if target.shape != result.shape:
            raise ValueError(f"out: shape {target.shape}; the result is {result.shape}")
        if target.dtype.name != dtype:
            raise ValueError(f"out: dtype {target.dtype.name}; out_dtype is {dtype}")
        np.copyto(target, result, casting="unsafe")
        return out
    result = result.astype(dtype, copy=False)
    return as_like(result, like if like is not None else frames.like)


def as_like(result: np.ndarray, like: Any) -> Any:
    """result as `like`'s kind of array: numpy for None or a numpy array, else
    the array library of like's type (torch.from_dlpack for a tensor), with
    no copy where the strides allow it."""
    if like is None or isinstance(like, np.ndarray):
        return result
    library = sys.modules.get(type(like).__module__.split(".")[0])
    from_dlpack = getattr(library, "from_dlpack", None)
    if from_dlpack is None:
        raise TypeError(f"like: {type(like).__name__}'s library has no from_dlpack")
    if any(s < 0 for s in result.strides) or not result.flags.writeable:
        result = np.ascontiguousarray(result)  # DLPack consumers take no negative strides
    return from_dlpack(result)


def engine_out(out: Any, frames: EngineFrames, layout: Layout, out_dtype: Any, clamp: Optional[bool],
               shape: Sequence[int]) -> Optional[np.ndarray]:
    """`out` itself when the engine can fill it directly (float32, C order,
    the engine's own layout, no clamping): no intermediate array."""
    if out is None or not isinstance(out, np.ndarray) or clamp or layout.portrait:
        return None
    if layout.channel_order == "bgr" and len(frames.shape) == 3 and frames.shape[2] == 3:
        return None
    if out_dtype is not None and np.dtype(out_dtype) != np.float32:
        return None
    if out.dtype != np.float32 or not out.flags.c_contiguous or not out.flags.writeable:
        return None
    engine_shape = tuple(shape) if frames.batched else tuple(shape[1:])
    if out.shape != engine_shape:
        return None
    return out if frames.batched else out[np.newaxis]
