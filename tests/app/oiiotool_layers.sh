#!/bin/sh
# CTest: a render with every AOV, listed by `oiiotool --info -v`, must show every
# layer's channels with their types, the crop as data window and every metadata
# key the application writes, with its value.
# Usage: oiiotool_layers.sh PATHTRACER OIIOTOOL SCENE
# Exits 77 (CTest's SKIP_RETURN_CODE for this test) when OIIOTOOL is not there.
set -eu
pathtracer=$1 oiiotool=$2 scene=$3
if ! command -v "$oiiotool" > /dev/null 2>&1; then
  echo "oiiotool not found ('$oiiotool'; Debian package openimageio-tools): skipped"
  exit 77
fi
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
"$pathtracer" "$scene" -o "$dir/out.exr" --quiet --spp 2 --seed 7 --accel bvh --width 48 --height 32 \
  --integrator path --crop-px 8,4,20,16 \
  --aov albedo,N,P:half,Z,IndexOB,IndexMA,emission,diffuse_direct,diffuse_indirect,specular_direct,specular_indirect:half,variance,samples,nonfinite
"$oiiotool" --info -v "$dir/out.exr" > "$dir/info.txt"
version=$("$pathtracer" --version | head -n 1 | cut -d' ' -f2)

status=0
expect() {
  if ! grep -qF -- "$1" "$dir/info.txt"; then
    echo "missing from oiiotool --info -v: $1"
    status=1
  fi
}
# Every channel with its type: R, G, B, A float; each AOV's default or asked type.
for c in R G B A; do expect "$c (float)"; done
for c in Z IndexOB.X IndexMA.X samples.X; do expect "$c (float)"; done
expect "nonfinite.X (half)"
for c in R G B; do
  expect "albedo.$c (half)"
  for layer in emission diffuse_direct diffuse_indirect specular_direct variance; do expect "$layer.$c (float)"; done
  expect "specular_indirect.$c (half)"
done
for c in X Y Z; do
  expect "N.$c (half)"
  expect "P.$c (half)"
done
expect "36 channel"
# The crop as data window in the full frame.
expect "20 x   16"
expect "pixel data origin: x=8, y=4"
expect "full/display size: 48 x 32"
# Every metadata key.
expect "pathtracer:renderTime: "
expect "pathtracer:spp: 2"
expect 'pathtracer:seed: "7"'
expect 'pathtracer:backend: "bvh'
expect 'pathtracer:integrator: "path"'
expect "pathtracer:version: \"$version\""
expect "pathtracer:partial: 0"
expect 'pathtracer:sampler: "sobol"'
expect 'pathtracer:filter: "box"'
expect "pathtracer:maxDepth: "
expect "pathtracer:clamp: 0"
expect "Software: \"pathtracer $version\""
expect "worldToCamera: "
expect "worldToNDC: "
expect "chromaticities: 0.64, 0.33, 0.3, 0.6, 0.15, 0.06, 0.3127, 0.329"
[ "$status" -eq 0 ] || cat "$dir/info.txt"
exit "$status"
