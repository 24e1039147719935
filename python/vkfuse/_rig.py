"""vkfuse.Rig and vkfuse.Dataset: the rig of `vkfuse run` from Python, and
recorded datasets read one frame at a time.

The Rig's keyword arguments are `vkfuse run`'s options, named as Python
spells them (--background-frames is background_frames), checked and
defaulted by the same code as the command line's; only those that write
files or publish are left to the command line. Its help lists them from that
one table.
"""
from __future__ import annotations

import inspect
import warnings
from typing import Any, Dict, Iterator, List, Optional, Tuple

from . import _vkfuse
from ._arrays import Layout
from ._conventions import mode_name, rule_name, wavelet_name

# run's options a Python rig leaves to the command line: they write files,
# publish, or count cycles (Rig.cycles(count) does).
_COMMAND_LINE_ONLY = {"--out", "--replace", "--record", "--publish", "--publish-encoding", "--publish-wait",
                      "--publish-frames", "--capture-only", "--cycles", "--duration"}
# Python's own defaults where they differ from the command line's: no
# background unless asked for (a live rig starts at once).
_PYTHON_DEFAULTS: Dict[str, Any] = {"background_frames": 0}
# How Python spells a value the command line spells its own way.
_CONVERT = {"mode": mode_name, "wavelet": wavelet_name,
            "base_rule": lambda r: rule_name(r, "base_rule"), "detail_rule": lambda r: rule_name(r, "detail_rule")}


def _options() -> Dict[str, Tuple[str, str, str]]:
    """Python name -> (option, value name, help) for each option a Python rig takes."""
    out = {}
    for option, value, help_text in _vkfuse.run_options:
        if option not in _COMMAND_LINE_ONLY:
            out[option[2:].replace("-", "_")] = (option, value, help_text)
    return out


_OPTIONS = _options()


def _text(name: str, value: Any) -> str:
    if name == "sequence" and not isinstance(value, str):
        return "+".join(",".join(str(int(v)) for v in setting) for setting in value)
    if name == "metrics" and not isinstance(value, str):
        return ",".join(value)
    if isinstance(value, bool) or value is None or isinstance(value, (list, tuple, dict)):
        raise TypeError(f"{name}: {type(value).__name__}; expected {_OPTIONS[name][1] or 'True'}")
    return str(value)


def _argv(options: Dict[str, Any]) -> List[str]:
    argv: List[str] = []
    for name, value in options.items():
        if name == "dataset":  # the name the first Python rig gave --replay
            name = "replay"
        if name not in _OPTIONS:
            hint = " (a vkfuse run option left to the command line)" if "--" + name.replace("_", "-") in \
                _COMMAND_LINE_ONLY else ""
            raise TypeError(f"Rig() got an unexpected keyword argument {name!r}{hint}")
        option, value_name, _ = _OPTIONS[name]
        if value is None:
            continue
        if not value_name:  # a flag
            if not isinstance(value, bool):
                raise TypeError(f"{name}: {type(value).__name__}; expected True or False")
            if value:
                argv.append(option)
            continue
        if name in _CONVERT:
            value = _CONVERT[name](value)
        values = value if name == "sensor" and isinstance(value, (list, tuple)) else [value]
        for v in values:
            argv += [option, _text(name, v)]
    return argv


class Rig:
    __doc__ = ""  # written below, from run's options

    def __init__(self, *, channel_order: str = "rgb", layout: str = "landscape", **options: Any) -> None:
        self._layout = Layout.of(channel_order, layout)
        # A replay's or a capture host's background count is theirs.
        live = not any(options.get(k) is not None for k in ("replay", "dataset", "source"))
        merged = dict(_PYTHON_DEFAULTS) if live else {}
        merged.update(options)
        self._rig = _vkfuse.Rig(_argv(merged))

    @property
    def sensors(self) -> List[str]:
        """The sensors' serials, in the order of each cycle's "sensors"."""
        return self._rig.sensors

    @property
    def backend(self) -> str:
        return self._rig.backend

    @property
    def sequence(self) -> List[List[int]]:
        return self._rig.sequence

    def next(self) -> Dict[str, Any]:
        """The next cycle: {"cycle", "capture_wait_s", "fuse_s", "sensors": [per
        sensor {"serial", "status" ("ok", "timeout", "failed"), "error",
        "metrics", "fused" (float32, the frames' layout), "frames" (uint8, one
        per setting), "idle", "window_span_s" (seconds from the oldest frame
        to the newest; window="sliding" fuses at every new clean frame)}]}."""
        cycle = self._rig.next()
        for sensor in cycle["sensors"]:
            if sensor["fused"] is not None:
                sensor["fused"] = self._layout.to_caller(sensor["fused"], 0)
            sensor["frames"] = [self._layout.to_caller(f, 0) for f in sensor["frames"]]
        return cycle

    def cycles(self, count: Optional[int] = None) -> Iterator[Dict[str, Any]]:
        """Cycles one by one as they come (a generator): count of them, or
        until a replay has played every recorded cycle, every sensor has
        failed, or the caller stops. Ctrl-C raises KeyboardInterrupt between
        cycles; close() (or a with block) then stops the sensors."""
        if count is not None and (isinstance(count, bool) or not isinstance(count, int) or count < 0):
            raise ValueError(f"count {count!r}: expected an int >= 0 or None")
        taken = 0
        while count is None or taken < count:
            if self._rig.cycles_left() == 0:
                return
            yield self.next()
            taken += 1

    def close(self) -> None:
        """Stops the sensors' capture threads and releases the sensors."""
        self._rig.close()

    def __enter__(self) -> "Rig":
        return self

    def __exit__(self, *exc: Any) -> None:
        self.close()


def _rig_help() -> str:
    lines = ["Sensors cycling through an LED sequence, fused every cycle: `vkfuse run`'s rig.",
             "",
             "Real DIGITs (sensor=serial or [serials]), simulated ones (sensors=N, or when none is",
             "plugged in), or a recorded dataset played back (replay=DIR). Python's defaults are the",
             "command line's but background_frames (0: the rig starts at once). mode, wavelet and the",
             "rules are spelled as vkfuse.fuse() spells them.",
             "",
             "channel_order, layout: how fused images and frames come back (as vkfuse.fuse()).",
             "Keyword arguments (the command line's options):"]
    for name, (option, value, help_text) in _OPTIONS.items():
        lines.append(f"  {name}{'=' + value if value else '=True'}: {help_text} ({option})")
    lines.append("  dataset=DIR: replay's former name")
    return "\n".join(lines)


Rig.__doc__ = _rig_help()
# help(vkfuse.Rig) and inspect show every option as a keyword argument.
Rig.__init__.__signature__ = inspect.Signature(  # type: ignore[attr-defined]
    [inspect.Parameter("self", inspect.Parameter.POSITIONAL_OR_KEYWORD),
     inspect.Parameter("channel_order", inspect.Parameter.KEYWORD_ONLY, default="rgb"),
     inspect.Parameter("layout", inspect.Parameter.KEYWORD_ONLY, default="landscape")] +
    [inspect.Parameter(name, inspect.Parameter.KEYWORD_ONLY, default=_PYTHON_DEFAULTS.get(name))
     for name in _OPTIONS])


class Dataset:
    """A recorded dataset (vkfuse sim, vkfuse run --record): a folder or an
    MCAP file (a path ending in .mcap); its sensors, objects and frames, each
    frame read from disk when reached. A recording cut short gives the whole
    cycles before the cut, with a RuntimeWarning saying where it stopped
    (also in `incomplete`)."""

    def __init__(self, directory: str) -> None:
        self._dataset = _vkfuse.Dataset(directory)
        if self._dataset.incomplete:
            warnings.warn(self._dataset.incomplete, RuntimeWarning, stacklevel=2)

    @property
    def incomplete(self) -> str:
        """Where reading a cut recording stopped, and why; "" when whole."""
        return self._dataset.incomplete

    @property
    def source(self) -> str:
        return self._dataset.source

    @property
    def sensors(self) -> List[str]:
        """The recorded sensors' serials."""
        return self._dataset.sensors

    def objects(self) -> List[str]:
        """Objects with frames, in recording order (backgrounds excluded)."""
        return self._dataset.objects()

    def frames(self, serial: str, object: str) -> Iterator[Dict[str, Any]]:
        """The frames of a take ('background' for the background takes), read
        one by one as the iterator is walked: dicts of pixels (H, W, 3)
        uint8, illumination (r, g, b), index, timestamp, cycle, file."""
        count = self._dataset.take_length(serial, object)  # errors now, not at the first next()
        return (self._dataset.frame(serial, object, i) for i in range(count))

