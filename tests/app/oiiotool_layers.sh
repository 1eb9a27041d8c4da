#!/bin/sh
# CTest: a render with AOVs, listed by `oiiotool --info -v`, must show every
# layer's channels with their types, the crop as data window and the metadata.
# Usage: oiiotool_layers.sh PATHTRACER OIIOTOOL SCENE
set -eu
pathtracer=$1 oiiotool=$2 scene=$3
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
"$pathtracer" "$scene" -o "$dir/out.exr" --quiet --spp 2 --width 48 --height 32 --integrator path \
  --aov albedo,N,P,Z,IndexOB,IndexMA,diffuse_direct,specular_indirect,variance,samples,nonfinite --crop-px 8,4,20,16
"$oiiotool" --info -v "$dir/out.exr" > "$dir/info.txt"
status=0
for want in "R (float)" "A (float)" "albedo.R (half)" "N.Z (half)" "P.X (float)" "Z (float)" "IndexOB (float)" \
            "IndexMA (float)" "diffuse_direct.B (float)" "specular_indirect.G (float)" "variance.R (float)" \
            "samples (float)" "nonfinite (half)" "20 x   16" "pixel data origin: x=8, y=4" \
            "full/display size: 48 x 32" "worldToCamera" "worldToNDC" "chromaticities" "pathtracer:spp: 2"; do
  if ! grep -qF "$want" "$dir/info.txt"; then
    echo "missing from oiiotool --info -v: $want"
    status=1
  fi
done
[ "$status" -eq 0 ] || cat "$dir/info.txt"
exit "$status"
