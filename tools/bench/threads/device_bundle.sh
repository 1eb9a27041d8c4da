#!/bin/bash
# Packs what tools/bench/threads/device_scaling.py needs on a bare machine that
# lacks the renderer's Debian libraries (e.g. the lent 16-core machine):
# build/pathtracer with its whole `ldd` closure including the dynamic loader
# (run through it, so the machine's own glibc does not matter), the Cornell box,
# and Crytek Sponza's geometry lit by a constant sky and the sun. The image
# module (OpenImageIO, ~350 MB of libraries) is not packed: the renders write
# PPM and read no image, so the environment map of sponza-env-sun.json is
# replaced by a constant sky.
#
#   tools/bench/threads/device_bundle.sh [EXE] [OUT_DIR] [NAME=EXE2 ...]  -> OUT_DIR/bundle.tar.xz (~27 MB with perf, ~21 MB without)
#   on the machine: tar -C /tmp/b -xJf bundle.tar.xz && python3 /tmp/b/device_scaling.py --rounds 2
# Each NAME=EXE2 adds a second build as NAME (same libraries; e.g. old=main's build for an A/B:
# device_scaling.py --exes new=pathtracer,old=old).
# perf (PERF_EXE, default /usr/bin/perf: Debian 12's perf 6.1, an ELF binary) is packed the same way,
# with its own ldd closure (libpython, libperl, libdw, ...: ~+9 MB to the archive), run through the
# packed loader as ./perf, for device_perf.py (docs/bench/threads.md, session 14). PACK_PERF=0 leaves
# it out (device_perf.py then still runs the timings and says that perf was missing).
set -euo pipefail
REPO=$(cd "$(dirname "$0")/../../.." && pwd)
EXE=${1:-$REPO/build/pathtracer}
OUT=${2:-$REPO/devcarry}
shift $(( $# < 2 ? $# : 2 ))
SHARED=${SHARED:-$REPO/../shared}
B=$(mktemp -d)
trap 'rm -rf "$B"' EXIT
mkdir -p "$OUT" "$B/lib" "$B/assets"
cp "$EXE" "$B/pathtracer.bin"
closure() { ldd "$1" | awk '/=>/{print $3} /ld-linux/{print $1}'; }
for l in $(closure "$EXE"); do cp -L "$l" "$B/lib/"; done
PACK_PERF=${PACK_PERF:-1}
PERF_EXE=${PERF_EXE:-/usr/bin/perf}
if [ "$PACK_PERF" = 1 ]; then
  if file -L "$PERF_EXE" | grep -q ELF; then
    cp -L "$PERF_EXE" "$B/perf.bin"
    # same names as the renderer's (libc, libstdc++, libm, the loader) are the same Debian files
    for l in $(closure "$PERF_EXE"); do cp -Ln "$l" "$B/lib/"; done
  else
    echo "device_bundle.sh: $PERF_EXE is not an ELF binary (a wrapper script?): perf not packed;" \
         "set PERF_EXE to the real binary or PACK_PERF=0" >&2
    exit 1
  fi
fi
cp "$SHARED/assets/sponza/sponza.obj" "$B/assets/"
cat > "$B/pathtracer" <<'EOS'
#!/bin/sh
D=$(dirname "$(readlink -f "$0")")
exec "$D/lib/ld-linux-x86-64.so.2" --library-path "$D/lib" "$D/pathtracer.bin" "$@"
EOS
chmod +x "$B/pathtracer"
[ -f "$B/perf.bin" ] && sed "s/pathtracer.bin/perf.bin/" "$B/pathtracer" > "$B/perf" && chmod +x "$B/perf"
for extra in "$@"; do
  name=${extra%%=*}
  cp "${extra#*=}" "$B/$name.bin"
  sed "s/pathtracer.bin/$name.bin/" "$B/pathtracer" > "$B/$name"
  chmod +x "$B/$name"
done
python3 - "$REPO/tools/bench/threads/sponza-env-sun.json" "$B/sponza-sky-sun.json" <<'EOP'
import json, sys
s = json.load(open(sys.argv[1]))
s.pop("environment")
s["render"]["background"] = [0.55, 0.65, 0.85]
s["shapes"][0]["file"] = "assets/sponza.obj"
json.dump(s, open(sys.argv[2], "w"), indent=1)
EOP
cp "$REPO/tools/bench/threads/device_scaling.py" "$REPO/tools/bench/threads/device_perf.py" \
   "$REPO/tools/bench/threads/perf_summary.py" "$REPO/scenes/cornell-box.json" "$B/"
chmod 755 "$B"   # mktemp's 700 would travel as the unpacked folder's mode
tar -C "$B" -cJf "$OUT/bundle.tar.xz" .
ls -la "$OUT/bundle.tar.xz"
