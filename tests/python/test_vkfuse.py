"""The Python module against its peers: PyWavelets, OpenCV and numpy as the
bench's Python pipelines use them (bench/peers/pipelines.py), computed in
float64, and the Vulkan backend against the CPU reference (docs/spec.md,
"Tolerances"). Run by ctest (python.vkfuse) with PYTHONPATH at the build's
python/ folder and VKFUSE_PEERS at bench/peers."""
import os
import subprocess
import sys
import threading
import time

import numpy as np
import pytest

import vkfuse

sys.path.insert(0, os.environ.get("VKFUSE_PEERS", os.path.join(os.path.dirname(__file__), "../../bench/peers")))
import pipelines  # noqa: E402  (the peers)
from concurrency import in_threads  # noqa: E402  (tests/python/concurrency.py)
from device import needs_vulkan  # noqa: E402  (tests/python/device.py)

H, W = 96, 128


def scene(seed, channels=3):
    """A gel-like frame: smooth shading, a pressed blob and fine texture, in [0, 1]."""
    rng = np.random.default_rng(seed)
    y, x = np.mgrid[0:H, 0:W] / np.array([H, W])[:, None, None]
    base = 0.3 + 0.4 * np.exp(-((x - 0.5) ** 2 + (y - 0.45) ** 2) / 0.05)
    tint = rng.uniform(0.5, 1.0, channels)
    img = base[..., None] * tint + 0.05 * rng.standard_normal((H, W, channels))
    return np.clip(img, 0, 1)


PEERS = {
    "wavelet": lambda f, levels, wavelet: pipelines.wavelet(f, wavelet, levels),
    "laplacian": lambda f, levels, wavelet: pipelines.laplacian(f, levels),
    "brovey": lambda f, levels, wavelet: pipelines.brovey(f),
    "channel-sum": lambda f, levels, wavelet: pipelines.channel_sum(f),
}
CASES = [("wavelet", 3, "bior4.4", 2), ("wavelet", 2, "haar", 3), ("wavelet", 2, "db2", 2),
         ("laplacian", 4, "bior4.4", 2), ("laplacian", 2, "bior4.4", 3), ("brovey", None, "bior4.4", 3),
         ("channel-sum", None, "bior4.4", 3)]


def frames_for(k):
    return [scene(10 + i) for i in range(k)]


@pytest.mark.parametrize("method,levels,wavelet,k", CASES)
def test_cpu_backend_matches_the_peers(method, levels, wavelet, k):
    frames = frames_for(k)
    got = vkfuse.fuse(frames, method=method, levels=levels, wavelet=wavelet, backend="cpu")
    want = PEERS[method](frames, levels, wavelet)
    assert got.dtype == np.float32 and got.shape == frames[0].shape
    # float32 output: the reference in double, rounded once.
    assert np.max(np.abs(got - want)) <= 1e-6


@needs_vulkan
@pytest.mark.parametrize("method,levels,wavelet,k", CASES)
def test_vulkan_backend_matches_the_reference(method, levels, wavelet, k):
    frames = frames_for(k)
    ref = vkfuse.fuse(frames, method=method, levels=levels, wavelet=wavelet, backend="cpu")
    got = vkfuse.fuse(frames, method=method, levels=levels, wavelet=wavelet, backend="vulkan")
    err = np.abs(got - ref)
    # Max-abs near-ties may flip a coefficient (docs/spec.md); everything else within 1e-5.
    over = int(np.count_nonzero(err > 1e-5))
    assert over <= err.size * 1e-3, f"{over} of {err.size} samples over 1e-5 (max {err.max():.3g})"


def test_uint8_frames_are_scaled_by_1_over_255():
    frames = [np.round(f * 255).astype(np.uint8) for f in frames_for(2)]
    as_float = [f / 255.0 for f in frames]
    got = vkfuse.fuse(frames, backend="cpu")
    want = vkfuse.fuse(as_float, backend="cpu")
    assert np.max(np.abs(got - want)) <= 1e-7


@pytest.mark.parametrize("backend", ["cpu", pytest.param("vulkan", marks=needs_vulkan)])
def test_gray_frames_give_a_gray_result(backend):
    frames = [f[..., 0].astype(np.float32) for f in frames_for(2)]
    got = vkfuse.fuse(frames, backend=backend)
    assert got.shape == (H, W)
    want = pipelines.wavelet([f.astype(np.float64) for f in frames], "bior4.4", 3)
    assert np.max(np.abs(got - want)) <= 1e-5


@pytest.mark.parametrize("backend,tol", [("cpu", 1e-9), pytest.param("vulkan", 1e-5, marks=needs_vulkan)])
def test_metrics_match_numpy(backend, tol):
    img, bg = scene(3), scene(4)
    m = vkfuse.metrics(img, background=bg, backend=backend)
    sharpness, contrast, diff = pipelines.metrics(img, bg)
    assert m["sharpness"] == pytest.approx(sharpness, rel=tol)
    assert m["contrast"] == pytest.approx(contrast, rel=tol)
    assert m["background_diff"] == pytest.approx(diff, rel=tol)
    assert set(vkfuse.metrics(img, backend=backend)) == {"sharpness", "contrast"}


@pytest.mark.parametrize("backend", ["cpu", pytest.param("vulkan", marks=needs_vulkan)])
def test_a_plan_runs_cycle_after_cycle_as_fuse_does(backend):
    plan = vkfuse.Plan(H, W, channels=3, frames=2, dtype="float32",
                       metrics=["sharpness", "contrast", "background_diff"], backend=backend)
    assert plan.backend == backend
    plan.set_background(scene(5).astype(np.float32))
    for seed in (20, 30, 40):
        frames = [scene(seed).astype(np.float32), scene(seed + 1).astype(np.float32)]
        fused, m = plan.run(frames)
        want = vkfuse.fuse(frames, backend="cpu")
        assert np.max(np.abs(fused - want)) <= 1e-5
        ref = vkfuse.metrics(want, background=scene(5).astype(np.float32), backend="cpu")
        for name in ("sharpness", "contrast", "background_diff"):
            assert m[name] == pytest.approx(ref[name], rel=1e-5)
    if backend == "vulkan":
        assert plan.cpp_cycle_ms(frames, runs=3) > 0
    else:
        with pytest.raises(ValueError, match="times the Vulkan plan"):
            plan.cpp_cycle_ms(frames)


def test_a_plan_refuses_what_it_was_not_built_for():
    plan = vkfuse.Plan(H, W, frames=2, dtype="uint8", backend="cpu")
    u8 = [np.zeros((H, W, 3), np.uint8)] * 2
    with pytest.raises(ValueError, match="3 given; the plan fuses 2"):
        plan.run(u8 + u8[:1])
    with pytest.raises(ValueError, match=rf"frames\[0\]: {H}x32x3; the plan takes {H}x{W}x3"):
        plan.run([np.zeros((H, 32, 3), np.uint8)] * 2)
    with pytest.raises(ValueError, match="dtype float32; the plan takes uint8"):
        plan.run([np.zeros((H, W, 3), np.float32)] * 2)


def test_bad_inputs_raise_value_error_naming_the_input():
    good = frames_for(2)
    with pytest.raises(ValueError, match=rf"frames\[1\]: shape \({H}, 32, 3\); frames\[0\] is \({H}, {W}, 3\)"):
        vkfuse.fuse([good[0], good[1][:, :32]], backend="cpu")
    with pytest.raises(ValueError, match=r"frames\[0\]: dtype int64"):
        vkfuse.fuse([np.zeros((H, W), np.int64)] * 2, backend="cpu")
    with pytest.raises(ValueError, match=r"reads as one \(H, W, C\) image"):
        vkfuse.fuse(good[0], backend="cpu")
    with pytest.raises(ValueError, match="no frames given"):
        vkfuse.fuse([], backend="cpu")
    with pytest.raises(ValueError, match="xyz"):
        vkfuse.fuse(good, method="xyz")
    with pytest.raises(ValueError, match="backend gpu"):
        vkfuse.fuse(good, backend="gpu")
    with pytest.raises(ValueError, match="levels"):
        vkfuse.fuse(good, levels=9, backend="cpu")


def test_non_finite_frames_raise_vkfuse_error():
    frames = frames_for(2)
    frames[1][3, 4, 0] = np.nan
    with pytest.raises(vkfuse.Error, match="NaN"):
        vkfuse.fuse(frames, backend="cpu")


def test_a_plan_lets_other_threads_run_while_it_works():
    """The GIL is released while a cycle is fused: a Python thread ticking
    meanwhile never waits anywhere near the length of the cycle (holding
    the lock, the plan would stall it for the whole cycle)."""
    plan = vkfuse.Plan(480, 640, frames=3, dtype="float32", backend="cpu")
    frames = [np.random.default_rng(i).random((480, 640, 3), np.float32) for i in range(3)]
    stop = threading.Event()
    longest_wait = [0.0]

    def tick():
        last = time.perf_counter()
        while not stop.is_set():
            now = time.perf_counter()
            longest_wait[0] = max(longest_wait[0], now - last)
            last = now

    t = threading.Thread(target=tick)
    t.start()
    time.sleep(0.01)
    try:
        start = time.perf_counter()
        plan.run(frames)
        cycle = time.perf_counter() - start
    finally:
        stop.set()
        t.join()
    assert cycle > 0.05, "the cycle is too short to tell"
    assert longest_wait[0] < cycle / 2, f"the ticking thread waited {longest_wait[0]:.3f} s of a {cycle:.3f} s cycle"


def test_the_simulated_digit_captures_each_setting_lit_alone():
    sim = vkfuse.SimDigit(object="coin", seed=3)
    white, green = sim.capture([(15, 15, 15), (0, 15, 0)])
    assert white.dtype == np.uint8 and white.shape == (240, 320, 3)
    w, g = white.reshape(-1, 3).mean(axis=0), green.reshape(-1, 3).mean(axis=0)
    assert g[1] > g[0] + 10 and g[1] > g[2] + 10, f"green-lit frame means {g}"
    assert w[0] > g[0] + 10, f"white-lit {w} vs green-lit {g}"
    fused = vkfuse.fuse([white, green], backend="cpu")
    assert fused.shape == (240, 320, 3)
    frame = sim.grab()
    assert frame["pixels"].shape == (240, 320, 3) and frame["index"] > 0
    with pytest.raises(ValueError, match="a DIGIT has 3"):
        sim.capture([(15, 15)])
    with pytest.raises(ValueError, match="unknown object|object"):
        vkfuse.SimDigit(object="teapot")


@pytest.mark.parametrize("backend", ["cpu", pytest.param("vulkan", marks=needs_vulkan)])
def test_a_rig_of_simulated_digits_yields_cycles_as_arrays_and_dicts(backend):
    rig = vkfuse.Rig(sensors=2, sequence=[(15, 15, 15), (0, 15, 0)], object="coin", backend=backend)
    assert rig.sensors == ["SIM-0001", "SIM-0002"] and rig.backend == backend
    cycles = list(rig.cycles(2))
    assert [c["cycle"] for c in cycles] == [0, 1]
    for cycle in cycles:
        for s in cycle["sensors"]:
            assert s["status"] == "ok" and s["error"] == ""
            frames = s["frames"]
            assert len(frames) == 2 and frames[0].dtype == np.uint8 and frames[0].shape == (240, 320, 3)
            # The rig fuses what it hands back: the same frames through vkfuse.fuse agree.
            np.testing.assert_allclose(s["fused"], vkfuse.fuse(frames, backend=backend), atol=2e-6, rtol=0)
            expected = vkfuse.metrics(s["fused"], backend="cpu")
            assert s["metrics"]["sharpness"] == pytest.approx(expected["sharpness"], rel=1e-5)
            assert s["metrics"]["contrast"] == pytest.approx(expected["contrast"], rel=1e-5)
    with pytest.raises(ValueError, match="sensors 0: expected a positive integer"):
        vkfuse.Rig(sensors=0)
    with pytest.raises(ValueError, match="level 16"):
        vkfuse.Rig(sequence=[(16, 0, 0)])


def test_a_sliding_rig_fuses_each_settings_newest_frame_at_every_clean_frame():
    rig = vkfuse.Rig(sensors=1, virtual_clock=True, window="sliding", method="brovey", backend="cpu")
    windows = [c["sensors"][0] for c in rig.cycles(4)]
    rig.close()
    for w in windows:
        assert w["status"] == "ok" and w["window_span_s"] == pytest.approx(1 / 30, abs=1e-6)
    # Each window keeps the other setting's frame and takes one new frame, the
    # settings taking turns.
    for before, after in zip(windows, windows[1:]):
        same = [np.array_equal(a, b) for a, b in zip(before["frames"], after["frames"])]
        assert sorted(same) == [False, True]
    with pytest.raises(ValueError, match="window both: expected cycle or sliding"):
        vkfuse.Rig(window="both")


@pytest.fixture(scope="module")
def recorded(tmp_path_factory):
    """A dataset `vkfuse sim` records: one object under the 8 settings of levels 0 and 15."""
    cli = os.environ.get("VKFUSE_CLI")
    if not cli:
        pytest.skip("VKFUSE_CLI (the vkfuse program) not given")
    out = tmp_path_factory.mktemp("dataset") / "coin"
    subprocess.run([cli, "sim", "--out", str(out), "--objects", "coin-heads", "--grid", "0,15"], check=True,
                   stdout=subprocess.DEVNULL)
    return out


def test_a_dataset_gives_its_frames_as_arrays(recorded):
    ds = vkfuse.Dataset(str(recorded))
    assert ds.source == "vkfuse sim" and len(ds.sensors) == 1 and ds.objects() == ["coin-heads"]
    frames = list(ds.frames(ds.sensors[0], "coin-heads"))
    assert len(frames) == 8 and len(list(ds.frames(ds.sensors[0], "background"))) == 8
    lit = {f["illumination"]: f["pixels"] for f in frames}
    assert set(lit) == {(r, g, b) for r in (0, 15) for g in (0, 15) for b in (0, 15)}
    green = lit[(0, 15, 0)].reshape(-1, 3).mean(axis=0)
    assert green[1] > green[0] + 10 and green[1] > green[2] + 10, f"green-lit frame means {green}"
    assert lit[(0, 0, 0)].mean() < lit[(15, 15, 15)].mean() / 4
    with pytest.raises(ValueError, match="no take of teapot"):
        ds.frames(ds.sensors[0], "teapot")
    with pytest.raises(vkfuse.Error):
        vkfuse.Dataset(str(recorded / "missing"))


def test_a_recording_as_mcap_gives_the_same_frames_and_a_cut_one_warns(recorded, tmp_path):
    cli = os.environ["VKFUSE_CLI"]
    mcap = tmp_path / "coin.mcap"
    subprocess.run([cli, "convert", str(recorded), str(mcap)], check=True, stdout=subprocess.DEVNULL,
                   stderr=subprocess.DEVNULL)
    folder, whole = vkfuse.Dataset(str(recorded)), vkfuse.Dataset(str(mcap))
    assert whole.incomplete == "" and whole.sensors == folder.sensors and whole.objects() == folder.objects()
    serial = folder.sensors[0]
    for a, b in zip(folder.frames(serial, "coin-heads"), whole.frames(serial, "coin-heads")):
        assert a["illumination"] == b["illumination"] and a["index"] == b["index"]
        assert np.array_equal(a["pixels"], b["pixels"])
    cut = tmp_path / "cut.mcap"
    cut.write_bytes(mcap.read_bytes()[: mcap.stat().st_size * 3 // 4])
    with pytest.warns(RuntimeWarning, match="cut.mcap: byte [0-9]+: .*using the [0-9]+ frames before it"):
        partial = vkfuse.Dataset(str(cut))
    assert partial.incomplete.startswith(str(cut))


def test_a_rig_replays_a_dataset_frame_for_frame(recorded):
    ds = vkfuse.Dataset(str(recorded))
    lit = {f["illumination"]: f["pixels"] for f in ds.frames(ds.sensors[0], "coin-heads")}
    rig = vkfuse.Rig(dataset=str(recorded), object="coin-heads", sequence=[(15, 15, 15), (0, 15, 0)], backend="cpu")
    (cycle,) = list(rig.cycles(1))
    (s,) = cycle["sensors"]
    assert s["status"] == "ok"
    assert np.array_equal(s["frames"][0], lit[(15, 15, 15)]) and np.array_equal(s["frames"][1], lit[(0, 15, 0)])
    np.testing.assert_allclose(s["fused"], vkfuse.fuse(s["frames"], backend="cpu"), atol=1e-7, rtol=0)


@needs_vulkan
def test_fuse_reuses_its_plans_without_mixing_them_up():
    """fuse() keeps a plan per configuration: results must not depend on what ran before, or alongside."""
    a, b = frames_for(2), [scene(30 + i)[:64, :80] for i in range(3)]
    first_a = vkfuse.fuse(a, backend="vulkan")
    first_b = vkfuse.fuse(b, method="laplacian", backend="vulkan")
    for _ in range(3):
        assert np.array_equal(vkfuse.fuse(a, backend="vulkan"), first_a)
        assert np.array_equal(vkfuse.fuse(b, method="laplacian", backend="vulkan"), first_b)
    pairs = [frames_for(2) if i % 2 else [scene(40 + i), scene(50 + i)] for i in range(8)]
    expected = [vkfuse.fuse(p, backend="vulkan") for p in pairs]
    results = [None] * len(pairs)

    def work(i):
        results[i] = vkfuse.fuse(pairs[i], backend="vulkan")

    in_threads(len(pairs), work)
    for got, want in zip(results, expected):
        assert np.array_equal(got, want)
