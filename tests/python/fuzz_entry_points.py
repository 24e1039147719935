"""Random arguments at vkfuse's Python entry points for a while (ctest
python.fuzz, label fuzz): shapes, dtypes, strides, values, keyword
arguments, layouts, out= arrays. Every call either returns a result of the
promised shape and dtype, or raises ValueError / TypeError (a bad argument,
one line naming it), vkfuse.Error (a value the engine refuses: NaN, Inf) or
MemoryError; never anything else, and the interpreter never crashes (a
crash fails the test with the signal). Reproducible: the seed and the call
are printed before each call is made.

    python3 fuzz_entry_points.py SECONDS [SEED]
"""
import sys
import time
import warnings

import numpy as np

import vkfuse

# Mostly dtypes the engine takes, so that calls get past the checks.
DTYPES = [np.uint8, np.uint8, np.uint16, np.float32, np.float32, np.float64, np.int32, np.bool_, np.complex64,
          np.float16]
METHODS = ["wavelet", "laplacian", "brovey", "channel-sum", "channel_sum", "magic", 3]
RULES = ["mean", "max-abs", "signed-max", "min", "max", "median", None]
MODES = ["periodization", "symmetric-lifting", "symmetric", "zero", 7]
ALLOWED = (ValueError, TypeError, vkfuse.Error, MemoryError)


def pick(rng, options):
    return options[int(rng.integers(len(options)))]


def values(rng, shape, dtype):
    kind = rng.integers(6)
    if np.issubdtype(dtype, np.integer):
        info = np.iinfo(dtype)
        return rng.integers(info.min, int(info.max) + 1, shape, dtype=dtype)
    if dtype == np.bool_:
        return rng.integers(0, 2, shape).astype(bool)
    a = rng.standard_normal(shape)
    if kind == 1:
        a *= 10.0 ** rng.integers(-45, 40)  # subnormal to huge
    elif kind == 2 and a.size:
        a.flat[int(rng.integers(a.size))] = pick(rng, [np.nan, np.inf, -np.inf])
    elif kind == 3:
        a[...] = 0.5  # flat
    return a.astype(dtype)


def frames(rng):
    """Frames as anything a caller might pass: stacks, lists, batches, views."""
    k, h, w = int(rng.integers(0, 5)), int(rng.integers(1, 48)), int(rng.integers(1, 48))
    c = pick(rng, [None, 1, 3, 3, 2, 4])
    dtype = pick(rng, DTYPES)
    shape = (k, h, w) if c is None else (k, h, w, c)
    if rng.random() < 0.2:
        shape = (int(rng.integers(1, 4)),) + shape  # a batch
    if rng.random() < 0.05:
        shape = shape[: int(rng.integers(1, len(shape)))]  # too few dimensions
    a = values(rng, shape, dtype)
    form = rng.integers(6)
    if form == 1 and a.ndim >= 3:
        a = a[..., ::2, :] if a.ndim >= 4 else a[:, ::2]  # strided
    elif form == 2 and a.ndim >= 4:
        a = a[..., ::-1]  # negative strides
    elif form == 3:
        return list(a) if a.ndim else a  # a list of frames
    elif form == 4 and a.ndim >= 2:
        frames_list = list(a)
        if frames_list:
            frames_list[-1] = values(rng, tuple(int(rng.integers(1, 9)) for _ in range(a.ndim - 1)), dtype)
        return frames_list  # mismatched shapes
    elif form == 5:
        return pick(rng, [None, "frames", 3.5, [None, None], [[1, 2], [3, 4]]])
    return a


def kwargs(rng):
    kw = {}
    if rng.random() < 0.5:
        kw["method"] = pick(rng, METHODS)
    if rng.random() < 0.3:
        kw["levels"] = pick(rng, [None, 0, 1, 2, 3, -1, 40, 2.5, True])
    if rng.random() < 0.1:
        kw["level"] = pick(rng, [None, 1, 2])
    if rng.random() < 0.3:
        kw["wavelet"] = pick(rng, ["haar", "db2", "bior2.2", "bior4.4", "db9", 1])
    if rng.random() < 0.2:
        kw["mode"] = pick(rng, MODES)
    for rule in ("base_rule", "detail_rule"):
        if rng.random() < 0.2:
            kw[rule] = pick(rng, RULES)
    if rng.random() < 0.3:
        kw["channel_order"] = pick(rng, ["rgb", "bgr", "BGR"])
    if rng.random() < 0.3:
        kw["layout"] = pick(rng, ["landscape", "digit-interface", "portrait"])
    if rng.random() < 0.2:
        kw["out_dtype"] = pick(rng, [None, np.uint8, "uint16", np.float64, "int8", object])
    if rng.random() < 0.2:
        kw["clamp"] = pick(rng, [None, True, False])
    kw["backend"] = pick(rng, ["cpu", "auto", "vulkan"])
    return kw


def one_call(rng, plans):
    what = rng.integers(4)
    if what == 0:
        f, kw = frames(rng), kwargs(rng)
        if rng.random() < 0.1:
            kw["out"] = np.zeros(tuple(int(rng.integers(1, 40)) for _ in range(int(rng.integers(2, 4)))),
                                 pick(rng, [np.float32, np.uint8, np.float64]))
        return "fuse", lambda: vkfuse.fuse(f, **kw)
    if what == 1:
        img = values(rng, (int(rng.integers(1, 40)), int(rng.integers(1, 40)), pick(rng, [1, 3, 2])),
                     pick(rng, DTYPES))
        bg = pick(rng, [None, img, img[..., :1], img.astype(np.float32)])
        kw = {k: v for k, v in kwargs(rng).items() if k in ("channel_order", "layout", "backend")}
        return "metrics", lambda: vkfuse.metrics(img, bg, **kw)
    if what == 2:
        h, w = int(rng.integers(8, 40)), int(rng.integers(8, 40))
        kw = {k: v for k, v in kwargs(rng).items() if k not in ("level",)}
        kw.pop("out_dtype", None)
        sensors = int(rng.integers(1, 3))
        args = (h, w, pick(rng, [1, 3]), int(rng.integers(1, 4)), pick(rng, ["uint8", np.float32, "uint16", "int"]))

        def make():
            plans.append((vkfuse.Plan(*args, sensors=sensors, **kw), args, sensors, kw.get("layout")))
            del plans[:-4]
        return "Plan", make
    if not plans:
        return "nothing", lambda: None
    plan, (h, w, c, k, dtype), sensors, layout = pick(rng, plans)
    if rng.random() < 0.3:
        f = frames(rng)
    else:  # frames of the plan's shape, mostly of its dtype, as a stack or a batch
        if layout == "digit-interface":
            h, w = w, h
        shape = (sensors, k, h, w) + ((c,) if c == 3 or rng.random() < 0.5 else ())
        if sensors == 1 and rng.random() < 0.5:
            shape = shape[1:]
        dtype = pick(rng, [dtype, dtype, dtype, np.float64, np.uint8])
        f = values(rng, shape, np.dtype(dtype) if dtype != "int" else np.int32)
    return "Plan.run", lambda: plan.run(f)


def main():
    seconds = float(sys.argv[1])
    seed = int(sys.argv[2]) if len(sys.argv) > 2 else int(time.time())
    print(f"seed {seed}", flush=True)
    rng = np.random.default_rng(seed)
    warnings.simplefilter("ignore", DeprecationWarning)
    np.seterr(all="ignore")
    warnings.simplefilter("ignore", RuntimeWarning)  # numpy's casts of huge values: the point of some calls
    end = time.monotonic() + seconds
    calls, outcomes, plans = 0, {}, []
    while time.monotonic() < end:
        name, call = one_call(rng, plans)
        try:
            call()
            outcome = "ok"
        except ALLOWED as e:
            message = str(e)
            if not message or "\n" in message:
                raise AssertionError(f"{name}: {type(e).__name__} with a message of {message.count(chr(10)) + 1} "
                                     f"lines: {message!r}")
            outcome = type(e).__name__
        outcomes[(name, outcome)] = outcomes.get((name, outcome), 0) + 1
        calls += 1
    print(f"{calls} calls in {seconds:.0f} s:", ", ".join(f"{n} {o} {c}" for (n, o), c in sorted(outcomes.items())))
    assert any(o == "ok" for (_, o) in outcomes), "no call succeeded: the fuzzer explores nothing"


if __name__ == "__main__":
    main()
