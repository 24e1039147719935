"""Builds the Python module with CMake for `pip install .` (pyproject.toml):
the compiled vkfuse._vkfuse from this tree's CMake project (the library is
linked in statically), the pure-Python package from python/vkfuse."""
import atexit
import os
import re
import shutil
import subprocess
import sys
import tempfile

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = os.path.dirname(os.path.abspath(__file__))


def version():
    with open(os.path.join(ROOT, "CMakeLists.txt"), encoding="utf-8") as f:
        return re.search(r"project\(vkfuse VERSION ([0-9.]+)", f.read()).group(1)


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        kept = os.environ.get("VKFUSE_BUILD_DIR")
        build = kept or tempfile.mkdtemp(prefix="vkfuse-pip-")
        if not kept:
            atexit.register(shutil.rmtree, build, True)
        if not os.path.exists(os.path.join(build, "CMakeCache.txt")):
            subprocess.run(["cmake", "-S", ROOT, "-B", build, "-DCMAKE_BUILD_TYPE=Release", "-DVKFUSE_BUILD_TESTS=OFF",
                            "-DVKFUSE_BUILD_BENCH=OFF", "-DVKFUSE_HIL=OFF", "-DVKFUSE_PYTHON=ON",
                            f"-DPython3_EXECUTABLE={sys.executable}"], check=True)
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL") or str(os.cpu_count() or 1)
        subprocess.run(["cmake", "--build", build, "--target", "vkfuse_python", "-j", jobs], check=True)
        built = os.path.join(build, "python", "vkfuse")
        module = [f for f in os.listdir(built) if f.startswith("_vkfuse") and f.endswith(".so")]
        if len(module) != 1:
            raise RuntimeError(f"{built}: expected one compiled _vkfuse module, found {module}")
        target = self.get_ext_fullpath(ext.name)
        os.makedirs(os.path.dirname(target), exist_ok=True)
        shutil.copyfile(os.path.join(built, module[0]), target)


# setuptools' own files (build/, *.egg-info) go to a scratch directory, not
# into the source tree, whose build/ is CMake's.
SCRATCH = tempfile.mkdtemp(prefix="vkfuse-setuptools-")
atexit.register(shutil.rmtree, SCRATCH, True)

setup(
    version=version(),
    options={"build": {"build_base": os.path.join(SCRATCH, "build")}, "egg_info": {"egg_base": SCRATCH}},
    packages=["vkfuse"],
    package_dir={"": "python"},
    package_data={"vkfuse": ["py.typed", "*.pyi"]},
    ext_modules=[Extension("vkfuse._vkfuse", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    zip_safe=False,
)
