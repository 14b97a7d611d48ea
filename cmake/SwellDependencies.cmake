# Finds every dependency of swell's design card. A missing one stops configure with the Debian
# package that provides it, so the message is the fix (scripts/run and scripts/test install them all).

include(FindPackageHandleStandardArgs)
find_package(PkgConfig)
if(NOT PkgConfig_FOUND)
  message(FATAL_ERROR "swell: pkg-config not found. Install it: sudo apt-get install pkg-config")
endif()

# swell_require(<what> <debian-package> <found-variable>)
function(swell_require what package found)
  if(NOT ${found})
    message(FATAL_ERROR
      "swell: ${what} not found. Install the Debian package: sudo apt-get install ${package}\n"
      "(scripts/run and scripts/test install everything swell needs)")
  endif()
endfunction()

# FFTW: pkg-config is the reliable route on Debian (fftw3 ships no CMake config).
# fftw3l (long double) is the oracle for sizes where the naive long-double DFT is too slow.
pkg_check_modules(FFTW3 QUIET IMPORTED_TARGET fftw3)
pkg_check_modules(FFTW3F QUIET IMPORTED_TARGET fftw3f)
pkg_check_modules(FFTW3L QUIET IMPORTED_TARGET fftw3l)
swell_require("FFTW (fftw3)" libfftw3-dev FFTW3_FOUND)
swell_require("FFTW single precision (fftw3f)" libfftw3-dev FFTW3F_FOUND)
swell_require("FFTW long double (fftw3l)" libfftw3-dev FFTW3L_FOUND)
# The threaded FFTW libraries have no .pc file of their own; they sit beside the main ones.
find_library(FFTW3_THREADS_LIBRARY fftw3_threads HINTS ${FFTW3_LIBRARY_DIRS})
find_library(FFTW3F_THREADS_LIBRARY fftw3f_threads HINTS ${FFTW3F_LIBRARY_DIRS})
swell_require("FFTW threads (libfftw3_threads)" libfftw3-dev FFTW3_THREADS_LIBRARY)
swell_require("FFTW threads (libfftw3f_threads)" libfftw3-dev FFTW3F_THREADS_LIBRARY)

find_package(GTest QUIET)
swell_require("GoogleTest" "libgtest-dev libgmock-dev" GTest_FOUND)

find_package(benchmark QUIET)
swell_require("Google Benchmark" libbenchmark-dev benchmark_FOUND)

find_package(Ceres QUIET)
swell_require("Ceres Solver" libceres-dev Ceres_FOUND)

# Eigen (Ceres's own dependency): the probe checks' small Hermitian eigenproblems.
find_package(Eigen3 3.3 QUIET NO_MODULE)
swell_require("Eigen" libeigen3-dev Eigen3_FOUND)

# find_package(OpenImageIO) fails on Debian 12 (its config names /usr/include/opencv4);
# pkg-config works.
pkg_check_modules(OpenImageIO QUIET IMPORTED_TARGET OpenImageIO)
swell_require("OpenImageIO" libopenimageio-dev OpenImageIO_FOUND)
# OpenEXRCore's chunk table and libdeflate's zlib inflater: the direct reader of scanline EXR
# frames (validation/src/io/exr_scanlines.cpp), several times faster than OpenImageIO's.
pkg_check_modules(OpenEXR QUIET IMPORTED_TARGET OpenEXR)
swell_require("OpenEXR (OpenEXRCore)" libopenexr-dev OpenEXR_FOUND)
pkg_check_modules(LIBDEFLATE QUIET IMPORTED_TARGET libdeflate)
swell_require("libdeflate" libdeflate-dev LIBDEFLATE_FOUND)

if(SWELL_WITH_VULKAN)
  find_package(Vulkan QUIET COMPONENTS glslc)
  swell_require("Vulkan headers and loader" libvulkan-dev Vulkan_FOUND)
  swell_require("glslc (GLSL to SPIR-V compiler)" glslc Vulkan_glslc_FOUND)
endif()
if(SWELL_WITH_MPI)
  find_package(MPI QUIET COMPONENTS CXX)
  swell_require("MPI (Open MPI, for swell sweep under mpirun)" "openmpi-bin libopenmpi-dev" MPI_CXX_FOUND)
endif()
# The VkFFT anchor benchmark is optional: a missing piece only marks it unavailable, with why.
include(SwellVkFFT)

# Libraries swell uses instead of writing their job again.
find_package(Boost 1.74 QUIET)                       # Boost.Math quadrature, special functions
swell_require("Boost.Math" libboost-math-dev Boost_FOUND)
find_package(nlohmann_json 3 QUIET)
swell_require("nlohmann-json" nlohmann-json3-dev nlohmann_json_FOUND)
find_package(CLI11 QUIET)
swell_require("CLI11" libcli11-dev CLI11_FOUND)
find_package(fmt QUIET)
swell_require("fmt" libfmt-dev fmt_FOUND)
pkg_check_modules(TOMLPLUSPLUS QUIET IMPORTED_TARGET tomlplusplus)
swell_require("toml++" libtomlplusplus-dev TOMLPLUSPLUS_FOUND)
# netCDF: 2-D spectra E(f, θ) from files (wavespectra's and WAVEWATCH III's layouts).
pkg_check_modules(NETCDF QUIET IMPORTED_TARGET netcdf)
swell_require("netCDF" libnetcdf-dev NETCDF_FOUND)
find_path(RANDOM123_INCLUDE_DIR Random123/philox.h)
swell_require("Random123" librandom123-dev RANDOM123_INCLUDE_DIR)

# The Python module (python/, docs/python.md): pybind11 on the Debian Python, whose NumPy,
# pytest and xarray scripts/common.sh installs (python3-numpy, python3-pytest, python3-xarray).
# Another Python (a virtual environment's, through pip) is given with -DPython_EXECUTABLE.
if(SWELL_WITH_PYTHON)
  if(NOT DEFINED Python_EXECUTABLE AND EXISTS /usr/bin/python3)
    set(Python_EXECUTABLE /usr/bin/python3 CACHE FILEPATH "The Python the swell module is built for")
  endif()
  find_package(Python 3.9 QUIET COMPONENTS Interpreter Development.Module)
  swell_require("Python 3 headers (Python.h)" python3-dev Python_Development.Module_FOUND)
  set(PYBIND11_FINDPYTHON ON)
  find_package(pybind11 CONFIG QUIET)
  swell_require("pybind11" pybind11-dev pybind11_FOUND)
endif()
