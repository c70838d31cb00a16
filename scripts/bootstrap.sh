#!/usr/bin/env bash
# One entry point for a fresh Debian 12 machine (run from anywhere):
#   scripts/bootstrap.sh render  install packages, build the kasumi program (Release; no tests,
#                                no benchmarks), render the default scene to out/default.exr
#                                and out/default.png
#   scripts/bootstrap.sh test    install packages, build Release with -Werror and run every
#                                test, then build with ASan+UBSan and run the unit tests
# Package installation is idempotent: only missing packages are installed. As root they are
# installed with apt-get; otherwise through `sudo -n` (never a password prompt); without root
# or sudo the script prints the `sudo apt-get install ...` line to run and exits 1.
set -euo pipefail

mode="${1:-}"
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
jobs="${KASUMI_JOBS:-$(nproc)}"

packages=(
  build-essential cmake pkg-config ca-certificates
  libopenvdb-dev libboost-dev libboost-iostreams-dev
  libembree-dev libtbb-dev libopenexr-dev libopencolorio-dev opencolorio-tools
  libglm-dev nlohmann-json3-dev libcli11-dev zlib1g-dev
  libgtest-dev libgmock-dev libbenchmark-dev clang-format
  pybind11-dev python3-dev python3-numpy python3-pytest
  ffmpeg
)

install_packages() {
  local missing=()
  for p in "${packages[@]}"; do
    if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
      missing+=("$p")
    fi
  done
  if [ "${#missing[@]}" -eq 0 ]; then
    echo "bootstrap: all ${#packages[@]} packages present"
    return
  fi
  local as_root=()
  if [ "$(id -u)" -ne 0 ]; then
    # A non-interactive sudo only: a password prompt would hang CI and scripted set-ups.
    if command -v sudo >/dev/null 2>&1 && sudo -n true 2>/dev/null; then
      as_root=(sudo -n)
    else
      echo "bootstrap: missing packages; install them as root, then run this again:" >&2
      echo "  sudo apt-get install --no-install-recommends ${missing[*]}" >&2
      exit 1
    fi
  fi
  echo "bootstrap: installing ${missing[*]}"
  "${as_root[@]}" env DEBIAN_FRONTEND=noninteractive apt-get update -q
  "${as_root[@]}" env DEBIAN_FRONTEND=noninteractive \
    apt-get install -y -q --no-install-recommends "${missing[@]}"
}

build() {  # build PRESET
  # Reuse earlier compilations when ccache is installed (not required: a fresh machine builds
  # everything). The base dir and no-hash-dir settings let a new clone at another path hit.
  if command -v ccache >/dev/null 2>&1; then
    export CMAKE_C_COMPILER_LAUNCHER="${CMAKE_C_COMPILER_LAUNCHER:-ccache}"
    export CMAKE_CXX_COMPILER_LAUNCHER="${CMAKE_CXX_COMPILER_LAUNCHER:-ccache}"
    export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$root}" CCACHE_NOHASHDIR="${CCACHE_NOHASHDIR:-1}"
  fi
  cmake --preset "$1" >/dev/null
  cmake --build --preset "$1" -j "$jobs"
}

case "$mode" in
  render)
    install_packages
    build release
    mkdir -p out
    ./build/release/apps/kasumi render data/scenes/fog_street.json \
      -o out/default.exr --preview out/default.png
    ;;
  test)
    install_packages
    build ci
    ctest --preset ci -j "$jobs"
    build asan
    ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
      LSAN_OPTIONS="suppressions=$PWD/tests/lsan.supp:print_suppressions=0" ctest --preset asan -j "$jobs"
    ;;
  *)
    echo "usage: scripts/bootstrap.sh render|test" >&2
    exit 2
    ;;
esac
