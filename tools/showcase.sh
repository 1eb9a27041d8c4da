#!/usr/bin/env bash
# README command 1: set up, build the renderer (only it: the tests are built by tools/test.sh),
# and render the showcase scene to a multi-layer EXR and a PNG.
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$repo/tools/setup.sh" render
out="${PT_OUT_DIR:-$repo/out}"
mkdir -p "$out"
# The EXR carries what a compositor or denoiser wants beside the beauty: the light-path split,
# albedo, normal and depth, per-pixel variance, and Cryptomatte mattes of objects and materials.
aovs=albedo,N,Z,diffuse_direct,diffuse_indirect,specular_direct,specular_indirect,emission,variance
aovs+=,CryptoObject,CryptoMaterial
"${PT_BUILD_DIR:-$repo/build}/pathtracer" "$repo/scenes/showcase.json" \
  -o "$out/showcase.exr" -o "$out/showcase.png" --aov "$aovs" "$@"
echo "showcase written to:"
echo "  $out/showcase.exr  (linear float EXR: beauty with coverage alpha, and the layers $aovs)"
echo "  $out/showcase.png  (sRGB display image)"
