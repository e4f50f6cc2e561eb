"""Builds the Python module femup with the project's CMake (docs/python.md).

`pip install --no-build-isolation .` runs this: build_ext configures the
project in a build folder (FEMUP_PIP_BUILD_DIR, default build-pip/) with
the interpreter that runs pip, builds the one target femup_python (the
extension femup._femup and the libraries it links) and copies the extension
into the wheel beside python/femup/*.py. Objects come from ccache when the
README's commands compiled them before (same flags, the project folder as
ccache's base; a build folder one level below the project folder, as build/
and build-pip/ are, finds them: ccache keys hold paths relative to it).
setuptools' own build folders go to build-pip/setuptools, never to the CMake
build folder build/.
"""

import glob
import os
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = os.path.dirname(os.path.abspath(__file__))
# The CMake build and, in its setuptools/ folder, setuptools' own
# (FEMUP_PIP_BUILD_DIR moves both, e.g. for the test that installs into a venv).
PIP_BUILD = os.path.abspath(os.environ.get("FEMUP_PIP_BUILD_DIR") or
                            os.path.join(ROOT, "build-pip"))
SETUPTOOLS_BUILD = os.path.join(PIP_BUILD, "setuptools")


class CMakeExtension(Extension):
    def __init__(self, name):
        super().__init__(name, sources=[])


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        build_dir = PIP_BUILD
        env = dict(os.environ, CCACHE_BASEDIR=ROOT, CCACHE_NOHASHDIR="1")
        configure = ["cmake", "-S", ROOT, "-B", build_dir, "-DCMAKE_BUILD_TYPE=Release",
                     "-DFEMUP_BUILD_TESTS=OFF", "-DFEMUP_BUILD_BENCHMARKS=OFF",
                     "-DFEMUP_BUILD_VALIDATION=OFF", "-DFEMUP_BUILD_PYTHON=ON",
                     f"-DPython3_EXECUTABLE={sys.executable}"]
        try:
            import pybind11
            configure.append(f"-Dpybind11_DIR={pybind11.get_cmake_dir()}")
        except ImportError:
            pass  # CMake looks for pybind11 itself
        if shutil.which("ninja"):
            configure += ["-G", "Ninja"]
        subprocess.check_call(configure, env=env)
        subprocess.check_call(["cmake", "--build", build_dir, "--target", "femup_python",
                               "-j", str(os.cpu_count() or 2)], env=env)
        built = glob.glob(os.path.join(build_dir, "python", "femup", "_femup*.so"))
        if len(built) != 1:
            raise RuntimeError(f"femup: expected one extension in {build_dir}/python/femup, "
                               f"found {built}")
        target = self.get_ext_fullpath(ext.name)
        os.makedirs(os.path.dirname(target), exist_ok=True)
        shutil.copyfile(built[0], target)


os.makedirs(SETUPTOOLS_BUILD, exist_ok=True)
setup(
    package_dir={"": "python"},
    packages=["femup"],
    ext_modules=[CMakeExtension("femup._femup")],
    cmdclass={"build_ext": CMakeBuild},
    options={"build": {"build_base": os.path.relpath(SETUPTOOLS_BUILD, ROOT)},
             "egg_info": {"egg_base": os.path.relpath(SETUPTOOLS_BUILD, ROOT)}},
    zip_safe=False,
)
