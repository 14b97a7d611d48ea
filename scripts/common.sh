# Shared by scripts/run and scripts/test: install what is missing, then configure and build.
# Sourced, not run. Set SWELL_BUILD_DIR to build elsewhere (default: build/ in the checkout).
set -euo pipefail

SWELL_ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
SWELL_BUILD_DIR="${SWELL_BUILD_DIR:-$SWELL_ROOT/build}"

# Every Debian 12 package swell builds, tests or runs with. The dependency check in
# cmake/SwellDependencies.cmake names the same packages when one is missing (gnuplot-nox, which
# draws `swell report`'s figures at run time, is not a build dependency). The last line is
# scripts/sanitize's: clang, its sanitizer and libFuzzer runtimes (only recommended by clang, so
# named here) and its OpenMP. openmpi-bin and libopenmpi-dev: swell sweep under mpirun (the
# default build is the MPI one; its tests run mpirun with 1 and 2 ranks). ccache: rebuilds after
# a change recompile only what changed, even after a fresh configure (swell_compiler_launcher).
# The Python module (python/, docs/python.md): pybind11-dev and python3-dev build it, for the
# Debian python3 whose python3-numpy it needs; python3-pytest runs its suite, python3-xarray and
# python3-netcdf4 its wavespectra interop.
SWELL_PACKAGES=(
  build-essential cmake pkg-config
  libfftw3-dev libgtest-dev libgmock-dev libbenchmark-dev libceres-dev libeigen3-dev libopenimageio-dev
  libopenexr-dev libdeflate-dev
  libvulkan-dev mesa-vulkan-drivers glslc vulkan-tools vulkan-validationlayers
  libvkfft-dev glslang-dev spirv-tools
  libboost-math-dev nlohmann-json3-dev libcli11-dev libfmt-dev libtomlplusplus-dev libnetcdf-dev
  librandom123-dev
  gnuplot-nox
  openmpi-bin libopenmpi-dev
  clang libclang-rt-14-dev libomp-14-dev
  ccache
  pybind11-dev python3-dev python3-numpy python3-pytest python3-xarray python3-netcdf4
)

swell_install_packages() {
  local missing=()
  for package in "${SWELL_PACKAGES[@]}"; do
    if ! dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed"; then
      missing+=("$package")
    fi
  done
  if [ ${#missing[@]} -eq 0 ]; then
    return 0
  fi
  echo "swell: installing missing Debian packages: ${missing[*]}"
  local sudo=()
  if [ "$(id -u)" -ne 0 ]; then
    command -v sudo >/dev/null || { echo "swell: need root or sudo to install: ${missing[*]}" >&2; exit 2; }
    sudo=(sudo)
  fi
  "${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get update -qq
  "${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends \
    "${missing[@]}"
}

# The CMake arguments that put ccache in front of the compilers, when it is installed.
swell_compiler_launcher() {
  if command -v ccache >/dev/null; then
    echo "-DCMAKE_CXX_COMPILER_LAUNCHER=ccache"
  fi
}

# Configures <build dir> with <cmake arguments…> unless it already is; a build folder configured
# before ccache was installed is configured again to use it.
swell_configure() {
  local build_dir="$1"
  shift
  local launcher
  launcher="$(swell_compiler_launcher)"
  if [ ! -f "$build_dir/CMakeCache.txt" ]; then
    cmake -S "$SWELL_ROOT" -B "$build_dir" $launcher "$@"
  elif [ -n "$launcher" ] && ! grep -q '^CMAKE_CXX_COMPILER_LAUNCHER:.*=ccache$' "$build_dir/CMakeCache.txt"; then
    cmake -S "$SWELL_ROOT" -B "$build_dir" $launcher
  fi
}

# Puts <build>/python on the Debian python3's path with a .pth file, so that after either
# command `python3 -c "import swell"` imports this build's module (docs/python.md): in
# /usr/local/lib/python3.X/dist-packages as root, in the user's site-packages otherwise. Not a
# pip install: the module stays the build tree's, rebuilt with it. Where `python3` on PATH is
# another interpreter of the same version (pyenv's, say), it gets the same .pth, with Debian's
# packages (NumPy) after its own.
swell_install_python_path() {
  local debian=/usr/bin/python3
  [ -x "$debian" ] || return 0
  local version
  version="$("$debian" -c 'import sys; print(sys.version_info[:2])')"
  local python site lines
  for python in "$debian" "$(command -v python3 || true)"; do
    [ -n "$python" ] || continue
    [ "$python" = "$debian" ] || [ "$(readlink -f "$python")" != "$(readlink -f "$debian")" ] || continue
    if [ "$("$python" -c 'import sys; print(sys.version_info[:2])')" != "$version" ]; then
      echo "swell: $python is not the Python $version the module is built for; use $debian"
      continue
    fi
    if [ "$(id -u)" -eq 0 ]; then
      site="$("$python" -c 'import site; print(site.getsitepackages()[0])')"
    else
      site="$("$python" -m site --user-site)"
    fi
    lines="$SWELL_BUILD_DIR/python"
    [ "$python" = "$debian" ] || lines+=$'\n/usr/lib/python3/dist-packages'
    mkdir -p "$site"
    printf '%s\n' "$lines" > "$site/swell-build.pth"
    echo "swell: $python imports swell from $SWELL_BUILD_DIR/python ($site/swell-build.pth)"
  done
}

swell_build() {
  # Configure once; later calls rebuild only what changed.
  swell_configure "$SWELL_BUILD_DIR" -DCMAKE_BUILD_TYPE=Release
  cmake --build "$SWELL_BUILD_DIR" -j "$(nproc)"
  swell_install_python_path
}
