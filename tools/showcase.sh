#!/usr/bin/env bash
# README command 1: set up, build, and render the showcase scene to an EXR and a PNG.
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$repo/tools/setup.sh"
out="${PT_OUT_DIR:-$repo/out}"
mkdir -p "$out"
"${PT_BUILD_DIR:-$repo/build}/pathtracer" "$repo/scenes/showcase.json" -o "$out/showcase.exr" -o "$out/showcase.png" "$@"
echo "showcase written to:"
echo "  $out/showcase.exr  (linear float EXR)"
echo "  $out/showcase.png  (sRGB display image)"
