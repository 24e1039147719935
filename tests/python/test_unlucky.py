"""The Python module used as an unlucky user would: one Plan from two
threads, memory running out, Ctrl-C in a long call, bounds on what a rig
takes, and messages that speak Python."""
import os
import signal
import subprocess
import sys
import textwrap
import threading

import numpy as np
import pytest

import vkfuse
from device import needs_vulkan



def run_python(code, timeout=240):
    """code in a fresh interpreter (a crash there is an exit status here)."""
    return subprocess.run([sys.executable, "-c", textwrap.dedent(code)], capture_output=True, text=True,
                          timeout=timeout, env=dict(os.environ))


@pytest.mark.parametrize("backend", ["cpu", pytest.param("vulkan", marks=needs_vulkan)])
def test_one_plan_from_two_threads_gives_each_its_own_result(backend):
    """Calls on one Plan from two threads take turns: every result is the
    one a single thread gets for its frames, and the interpreter exits
    cleanly (it once crashed at exit, status 139)."""
    r = run_python(f"""
        import threading
        import numpy as np
        import vkfuse
        rng = np.random.default_rng(1)
        inputs = [[rng.integers(0, 256, (96, 128, 3), dtype=np.uint8) for _ in range(2)] for _ in range(2)]
        plan = vkfuse.Plan(96, 128, frames=2, backend="{backend}")
        expected = [plan.run(f)[0] for f in inputs]
        bad = []
        def work(i):
            for _ in range(60):
                fused, m = plan.run(inputs[i])
                if not np.array_equal(fused, expected[i]):
                    bad.append(i)
        threads = [threading.Thread(target=work, args=(i,)) for i in range(2)]
        for t in threads: t.start()
        for t in threads: t.join()
        print("mismatches", len(bad))
    """)
    assert r.returncode == 0, r.stderr[-2000:]
    assert "mismatches 0" in r.stdout


@needs_vulkan
def test_memory_running_out_on_the_device_path_raises_memory_error():
    """Two 20000 x 20000 frames under a 6 GiB address-space limit: the
    Vulkan path raises MemoryError, as the CPU path does, never an internal
    message."""
    r = run_python("""
        import resource
        import numpy as np
        import vkfuse
        resource.setrlimit(resource.RLIMIT_AS, (6 << 30, 6 << 30))
        a = np.zeros((20000, 20000), np.uint8)
        for backend in ("cpu", "vulkan"):
            try:
                vkfuse.fuse([a, a], backend=backend)
                print(backend, "fused")
            except MemoryError as e:
                print(backend, "MemoryError", e)
            except Exception as e:
                print(backend, type(e).__name__, e)
    """)
    assert r.returncode == 0, r.stderr[-2000:]
    lines = dict(line.split(" ", 1) for line in r.stdout.splitlines())
    assert lines["cpu"].startswith("MemoryError"), r.stdout
    assert lines["vulkan"].startswith("MemoryError"), r.stdout
    assert "internal" not in r.stdout


def test_ctrl_c_stops_a_long_rig_loop_between_cycles():
    """SIGINT during a loop over Rig.cycles(200) raises KeyboardInterrupt at
    the next cycle, not after all 200 (the rig then goes on from where it stopped)."""
    rig = vkfuse.Rig(sensors=1, method="wavelet", backend="cpu")
    next(rig.cycles(1))
    timer = threading.Timer(0.3, lambda: os.kill(os.getpid(), signal.SIGINT))
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            for _ in rig.cycles(200):
                pass
    finally:
        timer.cancel()
    assert rig.next()["cycle"] < 200
    rig.close()


def test_a_rig_is_bounded_as_the_command_line_is():
    with pytest.raises(ValueError, match="sensors 1000: at most 64"):
        vkfuse.Rig(sensors=1000)
    with pytest.raises(ValueError, match="more than 16 settings in one cycle"):
        vkfuse.Rig(sequence=[(15, 15, 15)] * 17)


def test_messages_name_python_arguments_not_command_line_options():
    frames = [np.zeros((96, 128, 3)), np.ones((96, 128, 3))]
    with pytest.raises(ValueError) as e:
        vkfuse.fuse(frames, levels=9, backend="cpu")
    assert str(e.value).startswith("levels 9: a 96x128 image carries at most"), str(e.value)
    with pytest.raises(ValueError) as e:
        vkfuse.fuse([np.zeros((4, 4, 3))] * 2, backend="cpu")
    assert str(e.value).startswith("levels (default 3): a 4x4 image is too small"), str(e.value)
    with pytest.raises(ValueError) as e:
        vkfuse.fuse(frames, method="laplacian", base_rule="median", backend="cpu")
    assert "base_rule" in str(e.value) and "--" not in str(e.value), str(e.value)
    with pytest.raises(ValueError) as e:
        vkfuse.fuse(frames, method="magic", backend="cpu")
    assert str(e.value).startswith("method: unknown method \"magic\""), str(e.value)


@needs_vulkan
def test_fuse_without_a_backend_gives_the_vulkan_result_bit_for_bit():
    rng = np.random.default_rng(7)
    for method, k in (("wavelet", 2), ("laplacian", 3), ("brovey", 2), ("channel-sum", 3)):
        frames = [rng.integers(0, 256, (72, 100, 3), dtype=np.uint8) for _ in range(k)]
        assert np.array_equal(vkfuse.fuse(frames, method=method), vkfuse.fuse(frames, method=method,
                                                                             backend="vulkan")), method
