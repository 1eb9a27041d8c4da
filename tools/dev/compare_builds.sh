#!/usr/bin/env bash
# Are two builds' images bit-identical? For changes that must not change behaviour
# (refactoring): renders a fixed set of scenes x backends x integrators/samplers/AOVs with
# both executables and compares every pixel of every layer (idiff -fail 0).
#
#   bash tools/dev/compare_builds.sh OLD_PATHTRACER NEW_PATHTRACER
#
# Uses scenes/*.json, and the course files and Sponza from ../shared when present. Prints
# one line per difference and "identical: N renders" at the end; exits 1 on any difference.
set -u
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
old=$(readlink -f "$1"); new=$(readlink -f "$2")
command -v idiff >/dev/null || { echo "compare_builds: needs idiff (openimageio-tools)" >&2; exit 2; }
out=$(mktemp -d); trap 'rm -rf "$out"' EXIT
shared="$repo/../shared/seed-scenes"
scenes=("$repo"/scenes/*.json)
for s in "$shared"/path-of-light/examples/example.json "$shared"/cgr/*.json "$repo"/tools/bench/render/sponza-env.json; do
  [ -f "$s" ] && scenes+=("$s")
done
variants=("--accel=bvh --spp 2" "--accel=embree --spp 2"
          "--accel=bvh --integrator path --spp 4"
          "--accel=embree --integrator path --spp 4 --sampler jittered"
          "--accel=bvh --integrator path --spp 2 --aov albedo,N,P,Z,IndexOB,IndexMA --sampler random --filter gaussian")
n=0; fail=0
cd "$repo"
for s in "${scenes[@]}"; do
  for i in "${!variants[@]}"; do
    v=${variants[$i]}; name=$(basename "$s" .json)-$i.exr
    # shellcheck disable=SC2086
    "$old" "$s" -o "$out/old-$name" --width 96 --threads 2 --quiet $v >/dev/null 2>&1 || { echo "old build failed: $s $v"; continue; }
    # shellcheck disable=SC2086
    "$new" "$s" -o "$out/new-$name" --width 96 --threads 2 --quiet $v >/dev/null 2>&1 || { echo "DIFFERS (new build failed): $s $v"; fail=1; continue; }
    n=$((n + 1))
    idiff -fail 0 -failpercent 0 -warn 0 -a "$out/old-$name" "$out/new-$name" >/dev/null 2>&1 || { echo "DIFFERS: $s $v"; fail=1; }
  done
done
if [ $fail = 0 ]; then echo "identical: $n renders"; else echo "not identical"; fi
exit $fail
