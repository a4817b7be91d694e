"""`pip install .` for the strata Python package: CMake builds the module (strata._strata, with the
C++ libraries it needs) and setuptools packages it with python/strata's pure-Python part and type
stubs. Offline, with Debian's setuptools, wheel and pybind11 (no build isolation, nothing
downloaded):

    python3 -m venv --system-site-packages .venv
    .venv/bin/pip install --no-build-isolation .

`cmake --install build` installs the same package with the C++ one (docs/python.md). The CMake
build tree is build-pip/ (STRATA_PIP_BUILD_DIR to change it; STRATA_CMAKE_ARGS adds options); the
programs, tests, benchmarks and LCM parts are not built.
"""
import os
import shutil
import subprocess
import sys
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = Path(__file__).resolve().parent


def project_version():
    for line in (ROOT / "CMakeLists.txt").read_text().splitlines():
        if line.startswith("project(strata VERSION "):
            return line.split()[2]
    raise RuntimeError("setup.py: no project(strata VERSION ...) line in CMakeLists.txt")


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        build_dir = Path(os.environ.get("STRATA_PIP_BUILD_DIR", ROOT / "build-pip")).resolve()
        configure = [
            "cmake", "-S", str(ROOT), "-B", str(build_dir), "-DCMAKE_BUILD_TYPE=Release",
            "-DSTRATA_BUILD_TESTS=OFF", "-DSTRATA_BUILD_BENCH=OFF", "-DSTRATA_BUILD_APPS=OFF",
            "-DSTRATA_BUILD_LCM=OFF", "-DSTRATA_BUILD_PYTHON=ON",
            f"-DPython_EXECUTABLE={sys.executable}",
        ] + os.environ.get("STRATA_CMAKE_ARGS", "").split()
        if shutil.which("ninja"):
            configure += ["-G", "Ninja"]
        subprocess.check_call(configure)
        subprocess.check_call(["cmake", "--build", str(build_dir), "--target", "strata_python",
                               "--parallel", str(os.cpu_count() or 1)])
        built = sorted((build_dir / "python" / "strata").glob("_strata*.so"))
        if not built:
            raise RuntimeError(f"setup.py: CMake built no _strata module in {build_dir}/python/strata")
        target = Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(built[0], target)


setup(
    name="strata",
    version=project_version(),
    description="Dense multi-session mapping on Vulkan compute: TSDF, ESDF, meshes, change detection",
    packages=["strata"],
    package_dir={"": "python"},
    package_data={"strata": ["*.pyi", "py.typed"]},
    ext_modules=[Extension("strata._strata", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    python_requires=">=3.9",
    zip_safe=False,
)
