"""Builds adb._adb with the project's CMake (the module's target alone) and installs it with
the package's Python files. Options for CMake may be given in the environment:
ADB_CMAKE_ARGS="-DADB_BULLET_DOUBLE=ON", say."""

import os
import pathlib
import shlex
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

HERE = pathlib.Path(__file__).resolve().parent
ROOT = HERE.parent


class CMakeExtension(Extension):
    def __init__(self, name: str):
        super().__init__(name, sources=[])


class CMakeBuild(build_ext):
    def build_extension(self, ext: Extension) -> None:
        target = pathlib.Path(self.get_ext_fullpath(ext.name)).resolve()
        build = pathlib.Path(self.build_temp).resolve() / "cmake"
        build.mkdir(parents=True, exist_ok=True)
        configure = [
            "cmake", "-S", str(ROOT), "-B", str(build),
            "-DCMAKE_BUILD_TYPE=Release",
            "-DADB_BUILD_TESTS=OFF", "-DADB_BUILD_DEMOS=OFF", "-DADB_BUILD_PYTHON=ON",
            f"-DPython_EXECUTABLE={sys.executable}",
        ] + shlex.split(os.environ.get("ADB_CMAKE_ARGS", ""))
        subprocess.run(configure, check=True)
        jobs = str(os.cpu_count() or 2)
        subprocess.run(["cmake", "--build", str(build), "--target", "_adb", "-j", jobs],
                       check=True)
        built = sorted((build / "python" / "adb").glob("_adb*.so"))
        if not built:
            raise RuntimeError(f"the build left no _adb module in {build / 'python' / 'adb'}")
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(built[0], target)


setup(
    packages=["adb"],
    package_dir={"adb": "adb"},
    package_data={"adb": ["_adb.pyi", "py.typed"]},
    ext_modules=[CMakeExtension("adb._adb")],
    cmdclass={"build_ext": CMakeBuild},
    zip_safe=False,
)
