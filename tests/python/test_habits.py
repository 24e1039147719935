"""Scripts written with numpy, PyWavelets, OpenCV, PyTorch and digit-interface
habits, run unchanged: stacked arrays, batches, uint16, BGR portrait frames,
torch tensors in and out, level=, out=. Each is checked against the command
line's numbers (vkfuse fuse on the same frames as PNG files) or against the
plain call it must equal, on both backends."""
import os
import subprocess
import warnings

import numpy as np
import pytest

import vkfuse
from vkfuse import _arrays
from concurrency import in_threads  # tests/python/concurrency.py
from device import needs_vulkan  # tests/python/device.py

H, W = 96, 128
BACKENDS = ["cpu", pytest.param("vulkan", marks=needs_vulkan)]


def gel(seed, k=2, dtype=np.uint8):
    """K frames of a gel-like scene, (K, H, W, 3), in dtype's full range."""
    rng = np.random.default_rng(seed)
    y, x = np.mgrid[0:H, 0:W] / np.array([H, W])[:, None, None]
    base = 0.25 + 0.5 * np.exp(-((x - 0.5) ** 2 + (y - 0.45) ** 2) / 0.04)
    frames = np.clip(base[None, ..., None] * rng.uniform(0.4, 1.0, (k, 1, 1, 3))
                     + 0.06 * rng.standard_normal((k, H, W, 3)), 0, 1)
    if dtype == np.float64:
        return frames
    scale = np.iinfo(dtype).max if np.issubdtype(dtype, np.integer) else 1.0
    return np.round(frames * scale).astype(dtype) if scale != 1.0 else frames.astype(dtype)


def digit_interface(landscape):
    """What digit-interface's get_frame() hands out: OpenCV's BGR, transposed
    and flipped to portrait (cv2.transpose then cv2.flip(frame, 0))."""
    bgr = landscape[..., ::-1]
    return np.ascontiguousarray(np.flip(np.swapaxes(bgr, -3, -2), -3))


def cli_fuse(tmp_path, frames, *args):
    """vkfuse fuse on frames written as PNG files (OpenCV writes BGR)."""
    import cv2
    cli = os.environ.get("VKFUSE_CLI")
    if not cli:
        pytest.skip("VKFUSE_CLI (the vkfuse program) not given")
    names = []
    for k, f in enumerate(frames):
        names.append(str(tmp_path / f"f{k}.png"))
        assert cv2.imwrite(names[-1], np.ascontiguousarray(f[..., ::-1]))
    out = tmp_path / "fused.npy"
    subprocess.run([cli, "fuse", "-o", str(out), *args, *names], check=True)
    return np.load(out)


@pytest.mark.parametrize("backend", BACKENDS)
def test_digit_interface_frames_give_the_command_lines_numbers(tmp_path, backend):
    landscape = gel(1)
    frames = [digit_interface(f) for f in landscape]
    assert frames[0].shape == (W, H, 3)  # portrait
    got = vkfuse.fuse(frames, channel_order="bgr", layout="digit-interface", levels=2, backend=backend)
    want = cli_fuse(tmp_path, landscape, "--method", "wavelet", "--levels", "2", "--backend", backend)
    assert got.shape == (W, H, 3)
    np.testing.assert_allclose(got, digit_interface(want), atol=1e-5, rtol=0)
    # Metrics are the same numbers whatever the layout.
    bg = landscape[0].astype(np.float32) / 255
    mine = vkfuse.metrics(digit_interface(want), background=digit_interface(bg), channel_order="bgr",
                          layout="digit-interface", backend=backend)
    assert mine == vkfuse.metrics(want, background=bg, backend=backend)
    assert set(mine) == {"sharpness", "contrast", "background_diff"}


@pytest.mark.parametrize("backend", BACKENDS)
def test_uint16_frames_are_read_as_the_command_line_reads_16_bit_pngs(tmp_path, backend):
    frames = gel(2, dtype=np.uint16)
    got = vkfuse.fuse(frames, method="laplacian", backend=backend)
    want = cli_fuse(tmp_path, frames, "--method", "laplacian", "--backend", backend)
    np.testing.assert_allclose(got, want, atol=1e-6 if backend == "cpu" else 1e-5, rtol=0)
    plan = vkfuse.Plan(H, W, frames=2, dtype=np.uint16, method="laplacian", backend=backend)
    fused, _ = plan.run(frames)
    np.testing.assert_allclose(fused, want, atol=1e-6 if backend == "cpu" else 1e-5, rtol=0)


@pytest.mark.parametrize("backend", BACKENDS)
def test_stacks_lists_and_batches_agree(backend):
    stack = gel(3, k=3)
    single = vkfuse.fuse(list(stack), backend=backend)
    assert np.array_equal(vkfuse.fuse(stack, backend=backend), single)
    batch = np.stack([gel(4, k=3), stack, gel(5, k=3)])
    fused = vkfuse.fuse(batch, backend=backend)
    assert fused.shape == (3, H, W, 3)
    assert np.array_equal(fused[1], single)
    assert np.array_equal(vkfuse.fuse([list(b) for b in batch], backend=backend), fused)
    plan = vkfuse.Plan(H, W, frames=3, sensors=3, metrics=["sharpness", "contrast"], backend=backend)
    images, scores = plan.run(batch)
    assert plan.sensors == 3 and len(scores) == 3
    for s in range(3):
        np.testing.assert_allclose(images[s], vkfuse.fuse(batch[s], backend=backend), atol=1e-6, rtol=0)
        want = vkfuse.metrics(images[s], backend="cpu")
        assert scores[s]["sharpness"] == pytest.approx(want["sharpness"], rel=1e-5)
    with pytest.raises(ValueError, match="the plan fuses 3"):
        plan.run(stack)


def test_gray_stacks_and_batches():
    stack = gel(6, k=2)[..., 1]
    fused = vkfuse.fuse(stack, backend="cpu")
    assert fused.shape == (H, W)
    assert np.array_equal(fused, vkfuse.fuse(list(stack), backend="cpu"))
    plan = vkfuse.Plan(H, W, channels=1, frames=2, sensors=2, backend="cpu")
    images, _ = plan.run(np.stack([stack, stack]))
    assert images.shape == (2, H, W) and np.array_equal(images[0], fused)


@pytest.mark.parametrize("backend", BACKENDS)
def test_integer_output_is_clamped_not_wrapped(backend):
    frames = gel(7)
    raw = vkfuse.fuse(frames, backend=backend)
    assert raw.max() > 1.0 or raw.min() < 0.0, "the scene must overshoot for this test to mean anything"
    as_u8 = vkfuse.fuse(frames, out_dtype=np.uint8, backend=backend)
    assert as_u8.dtype == np.uint8
    assert np.array_equal(as_u8, np.rint(np.clip(raw, 0, 1) * 255).astype(np.uint8))
    as_u16 = vkfuse.fuse(frames, out_dtype="uint16", backend=backend)
    assert np.array_equal(as_u16, np.rint(np.clip(raw, 0, 1) * 65535).astype(np.uint16))
    clamped = vkfuse.fuse(frames, clamp=True, backend=backend)
    assert clamped.dtype == np.float32 and clamped.min() >= 0 and clamped.max() <= 1
    with pytest.raises(ValueError, match="clamp=False"):
        vkfuse.fuse(frames, out_dtype=np.uint8, clamp=False, backend=backend)


@pytest.mark.parametrize("backend", BACKENDS)
def test_out_fills_the_callers_array(backend):
    frames = gel(8)
    want = vkfuse.fuse(frames, backend=backend)
    out = np.full((H, W, 3), np.nan, np.float32)
    assert vkfuse.fuse(frames, out=out, backend=backend) is out
    assert np.array_equal(out, want)
    portrait = np.zeros((W, H, 3), np.uint8)
    vkfuse.fuse([digit_interface(f) for f in frames], channel_order="bgr", layout="digit-interface", out=portrait,
                backend=backend)
    assert np.array_equal(portrait, digit_interface(np.rint(np.clip(want, 0, 1) * 255).astype(np.uint8)))
    plan = vkfuse.Plan(H, W, frames=2, backend=backend)
    out[:] = 0
    fused, _ = plan.run(frames, out=out)
    assert fused is out and np.array_equal(out, want)
    with pytest.raises(ValueError, match="out: shape"):
        vkfuse.fuse(frames, out=np.zeros((H, W), np.float32), backend=backend)
    with pytest.raises(ValueError, match="out: read-only"):
        ro = np.zeros((H, W, 3), np.float32)
        ro.flags.writeable = False
        vkfuse.fuse(frames, out=ro, backend=backend)


def test_frames_are_copied_only_where_the_engine_cannot_read_them_as_they_are():
    """What fuse() hands the engine shares the caller's memory unless a copy is needed."""
    def copies(frames, **layout):
        given = _arrays.engine_frames(frames, "frames", _arrays.Layout.of(**layout) if layout else _arrays.Layout())
        return sum(not np.shares_memory(e, frames) for e in given.frames)

    u8 = gel(9, k=3)
    assert copies(u8) == 0
    assert copies(gel(9, k=3, dtype=np.float32)) == 0
    assert copies(gel(9, k=3, dtype=np.float64)) == 0  # the CPU path reads float64 as it is
    assert copies(np.stack([u8, u8])) == 0  # a batch
    assert copies(u8[:, ::2, ::2]) == 3  # strided: one copy per frame
    assert copies(gel(9, k=3, dtype=np.uint16)) == 3  # scaled to [0, 1]
    assert copies(np.stack([digit_interface(f) for f in u8]), channel_order="bgr", layout="digit-interface") == 3
    assert copies(u8[..., ::-1], channel_order="bgr") == 0  # BGR of a BGR view is the RGB memory itself


@pytest.mark.parametrize("backend", BACKENDS)
def test_torch_tensors_in_and_out(backend):
    torch = pytest.importorskip("torch")
    frames = gel(10, dtype=np.float32)
    want = vkfuse.fuse(frames, backend=backend)
    t = torch.from_numpy(frames)
    got = vkfuse.fuse(t, backend=backend)
    assert isinstance(got, torch.Tensor) and got.dtype == torch.float32
    assert np.array_equal(got.numpy(), want)
    as_numpy = vkfuse.fuse(t, like=np.empty(0), backend=backend)
    assert isinstance(as_numpy, np.ndarray)
    assert isinstance(vkfuse.fuse(frames, like=t, backend=backend), torch.Tensor)
    out = torch.zeros((H, W, 3), dtype=torch.float32)
    assert vkfuse.fuse(list(t), out=out, backend=backend) is out
    assert np.array_equal(out.numpy(), want)
    # Portrait BGR results (negative strides) still reach torch, contiguous.
    p = vkfuse.fuse(torch.from_numpy(np.stack([digit_interface(f) for f in frames])), channel_order="bgr",
                    layout="digit-interface", backend=backend)
    assert isinstance(p, torch.Tensor) and np.array_equal(p.numpy(), digit_interface(want))
    with pytest.raises(TypeError, match="frames"):
        vkfuse.fuse(torch.zeros((2, H, W, 3), requires_grad=True), backend=backend)


def test_tensors_in_device_memory_are_refused_by_name():
    class OnGpu:
        def __dlpack_device__(self):
            return (2, 0)  # kDLCUDA

        def __dlpack__(self, stream=None):
            raise AssertionError("must not be read")

    with pytest.raises(TypeError, match=r"frames\[0\]: a tensor in device memory"):
        vkfuse.fuse([OnGpu(), OnGpu()], backend="cpu")


def test_pywavelets_spellings():
    pywt = pytest.importorskip("pywt")
    frames = gel(11, dtype=np.float64)
    most = pywt.dwt_max_level(min(H, W), pywt.Wavelet("db2").dec_len)
    assert np.array_equal(vkfuse.fuse(frames, wavelet=pywt.Wavelet("db2"), level=None, backend="cpu"),
                          vkfuse.fuse(frames, wavelet="db2", levels=most, backend="cpu"))
    assert np.array_equal(vkfuse.fuse(frames, level=2, backend="cpu"), vkfuse.fuse(frames, levels=2, backend="cpu"))
    with pytest.raises(TypeError, match="level and levels"):
        vkfuse.fuse(frames, level=2, levels=2)
    with pytest.raises(ValueError, match="mode 'symmetric': PyWavelets' symmetric border is not implemented"):
        vkfuse.fuse(frames, mode="symmetric")
    with pytest.raises(ValueError, match="mode 'smooth'"):
        vkfuse.fuse(frames, mode="smooth")
    lifting = vkfuse.fuse(frames, mode="symmetric-lifting", backend="cpu")
    assert lifting.shape == (H, W, 3)
    with pytest.warns(DeprecationWarning, match="max-abs"):
        old = vkfuse.fuse(frames, detail_rule="max", backend="cpu")
    assert np.array_equal(old, vkfuse.fuse(frames, detail_rule="signed-max", backend="cpu"))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        vkfuse.fuse(frames, detail_rule="max_abs", backend="cpu")
    with pytest.raises(ValueError, match="detail_rule 'largest'"):
        vkfuse.fuse(frames, detail_rule="largest")


def test_dtypes_as_numpy_spells_them():
    for dtype in (np.uint8, np.dtype("uint8"), "uint8"):
        assert vkfuse.Plan(H, W, dtype=dtype, backend="cpu").backend == "cpu"
    vkfuse.Plan(H, W, dtype=np.float32, backend="cpu")
    with pytest.raises(TypeError, match="dtype: 'uint7' is not a dtype"):
        vkfuse.Plan(H, W, dtype="uint7")
    with pytest.raises(ValueError, match="dtype int32"):
        vkfuse.Plan(H, W, dtype=np.int32)
    with pytest.raises(TypeError, match="out_dtype"):
        vkfuse.fuse(gel(12), out_dtype="nonsense")


def test_one_plan_from_many_threads_is_serialised():
    plan = vkfuse.Plan(H, W, frames=2, backend="cpu")
    inputs = [gel(20 + i) for i in range(6)]
    want = [vkfuse.fuse(f, backend="cpu") for f in inputs]
    got = [None] * len(inputs)

    def work(i):
        for _ in range(3):
            got[i] = plan.run(inputs[i])[0]

    in_threads(len(inputs), work)
    for g, w in zip(got, want):
        assert np.array_equal(g, w)


def test_a_rig_hands_frames_back_as_digit_interface_does():
    with vkfuse.Rig(sensors=1, virtual_clock=True, backend="cpu", channel_order="bgr",
                    layout="digit-interface") as rig:
        (cycle,) = list(rig.cycles(1))
    s = cycle["sensors"][0]
    assert s["frames"][0].shape == (320, 240, 3) and s["fused"].shape == (320, 240, 3)
    np.testing.assert_allclose(s["fused"], vkfuse.fuse(s["frames"], channel_order="bgr", layout="digit-interface",
                                                       backend="cpu"), atol=2e-6, rtol=0)


def test_a_rig_takes_the_command_lines_options_by_their_python_names(tmp_path):
    with pytest.raises(TypeError, match="'out' \\(a vkfuse run option left to the command line\\)"):
        vkfuse.Rig(out=str(tmp_path / "x"))
    with pytest.raises(TypeError, match="unexpected keyword argument 'colour'"):
        vkfuse.Rig(colour="red")
    with pytest.raises(ValueError, match="^skip_threshold"):
        vkfuse.Rig(sensors=1, virtual_clock=True, background_frames=4, skip="tiles", skip_threshold=-1)
    config = tmp_path / "tuned.json"
    config.write_text('{"format": "vkfuse-config", "version": 1, "sequence": "15,0,0+0,15,0+0,0,15", '
                      '"method": "channel-sum"}')
    with vkfuse.Rig(sensors=1, virtual_clock=True, config=str(config), metrics=["sharpness"], backend="cpu") as rig:
        assert rig.sequence == [[15, 0, 0], [0, 15, 0], [0, 0, 15]]
        cycle = next(rig.cycles())
    s = cycle["sensors"][0]
    assert len(s["frames"]) == 3 and set(s["metrics"]) >= {"sharpness"}
    np.testing.assert_allclose(s["fused"], vkfuse.fuse(s["frames"], method="channel-sum", backend="cpu"),
                               atol=1e-7, rtol=0)


def test_help_names_every_argument():
    import inspect
    for f in (vkfuse.fuse, vkfuse.metrics, vkfuse.Plan, vkfuse.Plan.run):
        doc = inspect.getdoc(f)
        target = f.__init__ if inspect.isclass(f) else f
        for name in inspect.signature(target).parameters:
            if name != "self":
                assert name in doc, f"{f.__qualname__}: {name} not in its help"
    rig_doc = inspect.getdoc(vkfuse.Rig)
    for name in inspect.signature(vkfuse.Rig.__init__).parameters:
        if name != "self":
            assert name in rig_doc, f"Rig: {name} not in its help"


@needs_vulkan
def test_fused_images_stay_on_the_device_as_a_dlpack_tensor_and_an_fd():
    import ctypes
    frames = gel(13, k=2)
    want = vkfuse.fuse(frames, backend="vulkan")
    plan = vkfuse.Plan(H, W, frames=2, backend="vulkan", on_device=True)
    tensor, scores = plan.run(frames)
    assert isinstance(tensor, vkfuse.DeviceTensor) and tensor.shape == (1, H, W, 3)
    assert tensor.__dlpack_device__() == (7, 0)  # kDLVulkan
    assert scores["sharpness"] == pytest.approx(vkfuse.metrics(want, backend="cpu")["sharpness"], rel=1e-5)

    # The capsule: DLPack 0.6's DLManagedTensor, read as a consumer reads it.
    class DLTensor(ctypes.Structure):
        _fields_ = [("data", ctypes.c_void_p), ("device_type", ctypes.c_int), ("device_id", ctypes.c_int),
                    ("ndim", ctypes.c_int), ("code", ctypes.c_uint8), ("bits", ctypes.c_uint8),
                    ("lanes", ctypes.c_uint16), ("shape", ctypes.POINTER(ctypes.c_int64)),
                    ("strides", ctypes.POINTER(ctypes.c_int64)), ("byte_offset", ctypes.c_uint64)]

    capsule = tensor.__dlpack__()
    get = ctypes.pythonapi.PyCapsule_GetPointer
    get.restype, get.argtypes = ctypes.c_void_p, [ctypes.py_object, ctypes.c_char_p]
    t = DLTensor.from_address(get(capsule, b"dltensor"))
    assert (t.device_type, t.ndim, t.code, t.bits, t.lanes) == (7, 4, 2, 32, 1)
    assert [t.shape[i] for i in range(4)] == [1, H, W, 3] and not t.strides and t.data
    del capsule  # never consumed: its destructor frees it

    assert np.array_equal(tensor.numpy()[0], want)  # lavapipe's memory is host-visible
    fd = tensor.export_fd()
    try:
        imported = vkfuse.DeviceTensor.import_fd(fd, tensor.allocation_size, tensor.shape)
    finally:
        os.close(fd)
    assert np.array_equal(imported.numpy()[0], want)
    with pytest.raises(ValueError, match="do not fit allocation_size"):
        vkfuse.DeviceTensor.import_fd(0, 16, (1, H, W, 3))
    r, w = os.pipe()  # hostile fds are refused, never handed to the driver (one that waits on a pipe hangs)
    try:
        with pytest.raises(ValueError, match="a pipe, socket or directory"):
            vkfuse.DeviceTensor.import_fd(r, 1 << 20, (1, H, W, 3))
    finally:
        os.close(r), os.close(w)
    with open(__file__, "rb") as f:
        with pytest.raises(ValueError, match="less than allocation_size"):
            vkfuse.DeviceTensor.import_fd(f.fileno(), 1 << 30, (1, H, W, 3))
    with pytest.raises(ValueError, match="on_device: the images stay as the engine writes them"):
        vkfuse.Plan(H, W, on_device=True, layout="digit-interface")
    with pytest.raises(ValueError, match="on_device: needs the Vulkan backend"):
        vkfuse.Plan(H, W, on_device=True, backend="cpu")
