#!/usr/bin/env bash
# Installs whatever Debian 12 packages are missing (toolchain included) and builds
# the renderer in <repo>/build. Safe to re-run; works from any directory.
# Used by tools/showcase.sh and tools/test.sh (the README's two commands):
#
#   setup.sh render   what rendering needs: the libraries, and the `pathtracer` target only
#   setup.sh test     also the test and benchmark dependencies (GoogleTest, Google Benchmark,
#                     Python checks, Blender for the EXR round trip), and every target
set -euo pipefail

repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${PT_BUILD_DIR:-$repo/build}"
mode="${1:-test}"
case "$mode" in render|test) ;; *) echo "setup: unknown mode '$mode' (render or test)" >&2; exit 2;; esac

packages=(
  g++ cmake ninja-build pkg-config
  libembree-dev libtbb-dev
  libopenimageio-dev libopenexr-dev libopencolorio-dev
  nlohmann-json3-dev libcli11-dev libassimp-dev
)
if [ "$mode" = test ]; then
  packages+=(
    git openimageio-tools
    libgtest-dev libgmock-dev libbenchmark-dev
    python3 python3-jsonschema
    python3-matplotlib  # the study_quick test (tools/study/samplers/run_study.py --quick) plots; it skips without
    blender  # Blender 3.4 reading our EXRs (tests/app/test_blender_exr.cpp); it skips without
    openmpi-bin libopenmpi-dev  # pathtracer --mpi and its test (mpirun -np 3); the build works without (docs/distributed.md)
  )
fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if ((${#missing[@]})); then
  echo "setup: installing missing packages: ${missing[*]}"
  sudo_cmd=()
  if [ "$(id -u)" -ne 0 ]; then
    if command -v sudo >/dev/null 2>&1; then sudo_cmd=(sudo); else
      echo "setup: need root (or sudo) to install: ${missing[*]}" >&2; exit 1
    fi
  fi
  export DEBIAN_FRONTEND=noninteractive
  "${sudo_cmd[@]}" apt-get update -q
  "${sudo_cmd[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"
fi

jobs="$(nproc 2>/dev/null || echo 2)"
if [ "$mode" = test ]; then
  cmake -S "$repo" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE="${PT_BUILD_TYPE:-Release}" \
    -DPT_BUILD_TESTS=ON -DPT_BUILD_TOOLS=ON ${PT_CMAKE_ARGS:-} >/dev/null
  cmake --build "$build" -j "$jobs"
else
  # A first configure leaves the tests and tools out (their packages may be missing); a build
  # tree that tools/test.sh configured keeps them, and only the renderer is brought up to date.
  options=()
  [ -f "$build/CMakeCache.txt" ] || options=(-DPT_BUILD_TESTS=OFF -DPT_BUILD_TOOLS=OFF)
  cmake -S "$repo" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE="${PT_BUILD_TYPE:-Release}" \
    "${options[@]}" ${PT_CMAKE_ARGS:-} >/dev/null
  cmake --build "$build" -j "$jobs" --target pathtracer
fi
