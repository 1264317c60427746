#!/usr/bin/env bash
# Installs the Debian packages vdcloth needs to build, test and run; with the argument `fuzz`,
# also clang, its libFuzzer and sanitizer runtimes and its OpenMP (`make fuzz`).
# Idempotent: when every package is present it returns without touching apt.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  libeigen3-dev          # dense and sparse linear algebra
  libsuitesparse-dev     # CHOLMOD sparse Cholesky
  libopenblas0-openmp    # fast BLAS for CHOLMOD's dense kernels
  libblas-dev liblapack-dev  # linked directly by the supernodal factorization (OpenBLAS behind them)
  nlohmann-json3-dev     # scene and material files
  zlib1g-dev             # deflate for the PNG previews
  openmpi-bin libopenmpi-dev  # `mpirun -np N vdcloth run`: a run across processes and machines
  libgtest-dev libgmock-dev googletest
  libbenchmark-dev       # bench/
  libassimp-dev          # characters and cameras from glTF, FBX, Collada and X files
  assimp-testmodels      # CMU motion capture BVH files and rigged characters for the importers' tests
  ffmpeg                 # `vdcloth render --video`: the frames as an H.264 MP4
  libjs-three            # `vdcloth report`: its 3D viewer (three.js)
  libjs-chart.js         # `vdcloth report`: its plots (Chart.js)
  chromium-headless-shell  # the report's test opens it in a real browser
  blender                # the test of the Blender add-on (tools/blender/) runs it headless
  python3-numpy          # Blender's glTF exporter, which the add-on's export uses
)
if [ "${1:-}" = "fuzz" ]; then
  packages+=(
    clang                # the fuzz targets' compiler
    libclang-rt-14-dev   # libFuzzer and clang's AddressSanitizer and UBSan runtimes
    libomp-dev           # OpenMP for clang
  )
fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

echo "install-deps: installing ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
