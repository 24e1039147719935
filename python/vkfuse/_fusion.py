"""vkfuse.fuse() and vkfuse.metrics(): one call, any backend."""
from __future__ import annotations

from typing import Any, Optional

from . import _vkfuse
from ._arrays import Layout, as_array, engine_frames, engine_out, finish
from ._conventions import UNSET, spec_kwargs


def fuse(frames: Any, method: str = "wavelet", wavelet: Any = "bior4.4", levels: Optional[int] = None,
         mode: str = "periodization", base_rule: str = "mean", detail_rule: str = "max-abs", backend: str = "auto",
         *, level: Any = UNSET, channel_order: str = "rgb", layout: str = "landscape", out_dtype: Any = None,
         clamp: Optional[bool] = None, out: Any = None, like: Any = None) -> Any:
    """Fuses K frames lit differently into one image.

    frames: K frames of one shape and dtype: a list of (H, W) or (H, W, C)
        arrays (C 1 or 3), a stacked (K, H, W) or (K, H, W, C) array, or a
        batch of S sensors (S, K, H, W, C) / a list of S lists, fused in one
        submit. numpy arrays, torch CPU tensors or anything with __dlpack__
        or the array interface; uint8 (scaled by 1/255), uint16 (1/65535),
        float32 or float64; any strides (a copy is made only where the frame
        is not C-ordered landscape RGB already).
    method: "wavelet" (PyWavelets' 2-D DWT), "laplacian" (OpenCV's pyramids),
        "brovey" or "channel-sum" (K = 3: R, G, B from frames 1, 2, 3).
    wavelet: "haar", "db2", "bior2.2", "bior4.4", or a pywt.Wavelet of them.
    levels: DWT or pyramid levels; None: the method's default (wavelet 3,
        laplacian 4).
    level: PyWavelets' spelling: None means the most the image carries
        (pywt.dwt_max_level); give level or levels, not both.
    mode: "periodization" (pywt's, exactly; the default, where pywt's is
        "symmetric") or "symmetric-lifting" (vkfuse's whole-sample symmetric
        lifting); pywt's other modes are refused by name.
    base_rule, detail_rule: how the approximation band / top level and every
        detail band are combined: "mean", "max-abs" (the papers' "max":
        the coefficient of largest magnitude), "signed-max", "min".
    backend: "auto" (Vulkan when a usable device exists, else cpu), "vulkan",
        "cpu" (the double-precision reference).
    channel_order: "rgb", or "bgr" as OpenCV and digit-interface hand frames out.
    layout: "landscape" (the sensor's 320 x 240), or "digit-interface": its
        get_frame() portrait (transposed and flipped, 240 wide x 320 high).
        The result comes back in the frames' order and layout.
    out_dtype: float32 (default), float64, uint8 or uint16 (x 255 / 65535,
        rounded); None with out= given: out's dtype.
    clamp: clip to [0, 1] (wavelet and Laplacian fusion overshoot); None:
        only for integer output, which always clamps.
    out: an array (or torch tensor) of the result's shape and dtype to fill.
    like: return a tensor of like's library (torch.from_dlpack); None: the
        frames' kind (a torch tensor for torch frames), else numpy.

    Returns the fused image, (H, W[, C]); a batch gives (S, H, W[, C]).
    Bad arguments raise ValueError or TypeError naming the argument.
    """
    where = Layout.of(channel_order, layout)
    given = engine_frames(frames, "frames", where)
    h, w = given.frames[0].shape[:2]
    spec = spec_kwargs(method, wavelet, levels, level, mode, base_rule, detail_rule, h, w)
    engine_shape = (given.sensors,) + given.frames[0].shape
    direct = engine_out(out, given, where, out_dtype, clamp, engine_shape)
    fused = _vkfuse.fuse(given.frames, sensors=given.sensors, backend=backend, out=direct, **spec)
    if direct is not None:
        return out
    return finish(fused, given, where, out_dtype, clamp, out, like)


def metrics(image: Any, background: Any = None, backend: str = "auto", *, channel_order: str = "rgb",
            layout: str = "landscape") -> Any:
    """Sharpness, RMS contrast and, with a background, the mean absolute
    difference from it (docs/spec.md, "Metrics").

    image: one (H, W) or (H, W, C) image (dtypes as fuse() takes them), or a
        list / stacked (N, H, W, C) array of them: a list of dicts then.
    background: an image of the same shape and dtype, or None.
    backend: as fuse().
    channel_order, layout: as fuse(); the numbers do not depend on them
        (images are scored as the sensor's landscape RGB).
    """
    where = Layout.of(channel_order, layout)
    if not isinstance(image, (list, tuple)):
        image = as_array(image, "image")
    if isinstance(image, (list, tuple)) or image.ndim == 4:
        return [metrics(x, background, backend, channel_order=channel_order, layout=layout) for x in image]
    img = engine_frames(image, "image", where, single=True).frames[0]
    bg = None
    if background is not None:
        bg = engine_frames(background, "background", where, single=True).frames[0]
    return _vkfuse.metrics(img, bg, backend)
