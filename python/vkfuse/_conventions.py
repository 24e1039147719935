"""Names as numpy, PyWavelets and the fusion papers spell them, mapped onto
the engine's (the command line's): dtypes, level/levels, wavelets, border
modes and coefficient rules. Each function raises ValueError or TypeError
with one line that names the argument."""
from __future__ import annotations

import warnings
from typing import Any, Optional, Tuple

import numpy as np

from . import _vkfuse

# Frames the engine takes: 8-bit and 16-bit camera samples (scaled by 1/255
# and 1/65535), float32 and float64 values.
INPUT_DTYPES: Tuple[str, ...] = ("uint8", "uint16", "float32", "float64")
# What a result can be returned as: float32 (the engine's), float64, or
# camera samples again (scaled, rounded and clamped to [0, 1] first).
OUTPUT_DTYPES: Tuple[str, ...] = ("float32", "float64", "uint8", "uint16")

# PyWavelets' border modes (pywt.Modes.modes). vkfuse computes pywt's
# "periodization" exactly; its own whole-sample symmetric lifting (the
# command line's --mode symmetric) is no pywt mode, so Python names it
# "symmetric-lifting" and pywt's "symmetric" is refused rather than computed
# differently.
PYWT_MODES: Tuple[str, ...] = ("zero", "constant", "symmetric", "periodic", "smooth", "periodization", "reflect",
                               "antisymmetric", "antireflect")
MODES = {"periodization": "periodization", "symmetric-lifting": "symmetric"}

# Rules as Python spells them -> the engine's names. The fusion papers'
# "max" (choose-max) selects the coefficient of largest magnitude: that is
# "max-abs". The signed maximum is "signed-max"; a bare "max" still means
# it, with a DeprecationWarning, because it reads as the papers' rule.
RULES = {"max-abs": "max-abs", "mean": "mean", "signed-max": "max", "min": "min"}

METHODS: Tuple[str, ...] = ("wavelet", "laplacian", "brovey", "channel-sum")


class _Unset:
    """The default of `level`, which None would not tell apart from "not given"."""

    def __repr__(self) -> str:
        return "<not given>"


UNSET: Any = _Unset()


def dtype_name(dtype: Any, name: str, allowed: Tuple[str, ...]) -> str:
    """A numpy dtype, a type such as np.uint8 or a name such as "uint8"."""
    try:
        d = np.dtype(dtype)
    except TypeError:
        raise TypeError(f"{name}: {dtype!r} is not a dtype (expected {', '.join(allowed)})") from None
    if d.name not in allowed:
        raise ValueError(f"{name}: dtype {d.name}; expected {', '.join(allowed)}")
    return d.name


def method_name(method: Any) -> str:
    if not isinstance(method, str):
        raise TypeError(f"method: {type(method).__name__}; expected a name ({', '.join(METHODS)})")
    return method.replace("_", "-")


def wavelet_name(wavelet: Any) -> str:
    """A wavelet by name ("bior4.4") or a pywt.Wavelet of a family vkfuse has."""
    if isinstance(wavelet, str):
        return wavelet
    name = getattr(wavelet, "name", None)
    if isinstance(name, str) and hasattr(wavelet, "filter_bank"):
        return name
    raise TypeError(f"wavelet: {type(wavelet).__name__}; expected a name or a pywt.Wavelet")


def mode_name(mode: Any) -> str:
    if not isinstance(mode, str):
        raise TypeError(f"mode: {type(mode).__name__}; expected a name (periodization or symmetric-lifting)")
    if mode in MODES:
        return MODES[mode]
    if mode in PYWT_MODES:
        raise ValueError(f"mode {mode!r}: PyWavelets' {mode} border is not implemented; vkfuse has 'periodization' "
                         "(pywt's, exactly) and 'symmetric-lifting' (whole-sample symmetric lifting, no pywt mode)")
    raise ValueError(f"mode {mode!r}: unknown (expected periodization or symmetric-lifting)")


def rule_name(rule: Any, name: str) -> str:
    if not isinstance(rule, str):
        raise TypeError(f"{name}: {type(rule).__name__}; expected a name ({', '.join(RULES)})")
    spelled = rule.replace("_", "-")
    if spelled == "max":
        warnings.warn(f"{name}='max' is the signed maximum; the fusion papers' 'max' (choose-max) is 'max-abs'. "
                      "Say 'signed-max' or 'max-abs'.", DeprecationWarning, stacklevel=4)
        return "max"
    if spelled not in RULES:
        raise ValueError(f"{name} {rule!r}: unknown rule (expected {', '.join(RULES)})")
    return RULES[spelled]


def levels_of(levels: Optional[int], level: Any, method: str, wavelet: str, height: int, width: int) -> Optional[int]:
    """`levels` (None: the method's default: laplacian 4, wavelet 3) or pywt's
    `level` (None: the most the image carries, as pywt.wavedec2)."""
    if level is UNSET:
        count = levels
    elif levels is not None:
        raise TypeError("level and levels: give one (level is pywt's spelling, None meaning the maximum)")
    elif level is None:
        most = _vkfuse.max_levels(method, wavelet, height, width)
        count = most if most > 0 else None
    else:
        count = level
    if count is None:
        return None
    if isinstance(count, bool) or not isinstance(count, (int, np.integer)):
        raise TypeError(f"levels: {type(count).__name__}; expected an int or None")
    return int(count)


def spec_kwargs(method: Any, wavelet: Any, levels: Optional[int], level: Any, mode: Any, base_rule: Any,
                detail_rule: Any, height: int, width: int) -> dict:
    """The engine's keyword arguments for one fusion of frames height x width (landscape)."""
    m, w = method_name(method), wavelet_name(wavelet)
    return {"method": m, "wavelet": w, "levels": levels_of(levels, level, m, w, height, width),
            "mode": mode_name(mode), "base_rule": rule_name(base_rule, "base_rule"),
            "detail_rule": rule_name(detail_rule, "detail_rule")}
