"""`pip install` of this checkout (docs/python.md §1): builds the _swell extension with CMake (the
same build as scripts/run's, for the installing Python: -DPython_EXECUTABLE) into build-pip/,
and puts it, with the TIFF/PNG reader module, into the package python/swell. setuptools' own
build folder goes there too, out of CMake's build/."""
import os
import pathlib
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

SOURCE = pathlib.Path(__file__).resolve().parent
(SOURCE / "build-pip").mkdir(exist_ok=True)  # setuptools' egg-info and build folders go there


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        build = pathlib.Path(os.environ.get("SWELL_PIP_BUILD_DIR", SOURCE / "build-pip")).resolve()
        configure = ["cmake", "-S", str(SOURCE), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release",
                     f"-DPython_EXECUTABLE={sys.executable}", "-DSWELL_BUILD_TESTS=OFF",
                     "-DSWELL_BUILD_BENCHMARKS=OFF"]
        if shutil.which("ccache"):
            configure.append("-DCMAKE_CXX_COMPILER_LAUNCHER=ccache")
        subprocess.run(configure, check=True)
        subprocess.run(["cmake", "--build", str(build), "--target", "_swell", "swell_openimageio",
                        "-j", str(os.cpu_count() or 1)], check=True)
        target = pathlib.Path(self.get_ext_fullpath(ext.name)).parent
        target.mkdir(parents=True, exist_ok=True)
        package = build / "python" / "swell"
        for built in package.glob("_swell*.so"):
            shutil.copy2(built, target / built.name)
        shutil.copy2(build / "validation" / "libswell_openimageio.so",
                     target / "libswell_openimageio.so")


setup(ext_modules=[Extension("swell._swell", sources=[])], cmdclass={"build_ext": CMakeBuild},
      options={"build": {"build_base": str(SOURCE / "build-pip" / "setuptools")},
               "egg_info": {"egg_base": str(SOURCE / "build-pip")}})
