#!/usr/bin/env bash
# Builds the libFuzzer harnesses (tests/fuzz: scene, ply, obj, film_state,
# checkpoint, shard) with clang, AddressSanitizer and UndefinedBehaviorSanitizer in
# build-fuzz/, and runs each for SECONDS (default 600), one after the other.
#
#   tools/dev/fuzz.sh [SECONDS] [HARNESS...]      e.g. tools/dev/fuzz.sh 60 ply, tools/dev/fuzz.sh 600 checkpoint
#
# Corpora grow in build-fuzz/fuzz-corpus/<harness>/ (kept between runs, never
# committed); seeds are assembled from the repository (scenes, bad scenes,
# hostile files, tests/fuzz/seeds) and ../shared when present. Every crash,
# timeout, leak or out-of-memory input is copied into
# tests/hostile/fuzz-regressions/<harness>/, where test_fuzz_regressions
# replays it from then on. Logs: build-fuzz/fuzz-logs/<harness>.log. Exit
# status 1 if anything was found.
set -euo pipefail

repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
build="${PT_FUZZ_BUILD_DIR:-$repo/build-fuzz}"
seconds="${1:-600}"
shift || true
harnesses=("$@")
((${#harnesses[@]})) || harnesses=(scene ply obj film_state checkpoint shard)
shared="$repo/../shared"

command -v clang++ >/dev/null || { echo "fuzz: clang++ is needed (apt-get install clang)" >&2; exit 2; }
cmake -S "$repo" -B "$build" -G Ninja -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
      -DPT_FUZZ=ON -DPT_BUILD_TOOLS=OFF >/dev/null
targets=()
for h in "${harnesses[@]}"; do targets+=("fuzz_$h"); done
cmake --build "$build" --target "${targets[@]}" -j "$(nproc 2>/dev/null || echo 2)"

# Seeds, copied fresh (libFuzzer reads them, and adds what it finds to the corpus).
seed_files() {
  local dirs=() pattern
  case "$1" in
    scene) dirs=(scenes tests/bad-scenes tests/hostile/cases tests/stability/scenes tests/fuzz/seeds/scene)
           pattern='*.json' ;;
    ply)   dirs=(scenes/assets tests/hostile/files tests/fuzz/seeds/ply); pattern='*.ply' ;;
    obj)   dirs=(tests/hostile/files tests/fuzz/seeds/obj); pattern='*.obj' ;;
    film_state) dirs=(tests/fuzz/seeds/film_state); pattern='*.bin' ;;
    checkpoint) dirs=(tests/fuzz/seeds/checkpoint); pattern='*.ckpt' ;;
    shard) dirs=(tests/fuzz/seeds/shard); pattern='*.ptshard' ;;
  esac
  for d in "${dirs[@]}"; do [ -d "$repo/$d" ] && find "$repo/$d" -maxdepth 1 -type f -name "$pattern"; done
  case "$1" in  # ../shared beside the checkout, when present
    scene) [ -d "$shared/seed-scenes" ] && find "$shared/seed-scenes" -name '*.json' ;;
    ply)   [ -d "$shared/assets/meshes" ] && find "$shared/assets/meshes" -name '*res4.ply' ;;
    obj)   [ -d "$shared/assets/cornell" ] && find "$shared/assets/cornell" -name '*.obj' ;;
  esac
  return 0
}

# The OBJ harness writes each input to a file (load_obj reads files): keep it in memory.
[ -z "${TMPDIR:-}" ] && [ -w /dev/shm ] && export TMPDIR=/dev/shm

found=0
for h in "${harnesses[@]}"; do
  corpus="$build/fuzz-corpus/$h" seeds="$build/fuzz-seeds/$h" artifacts="$build/fuzz-artifacts/$h"
  rm -rf "$seeds" "$artifacts"
  mkdir -p "$corpus" "$seeds" "$artifacts" "$build/fuzz-logs"
  seed_files "$h" | while read -r f; do cp "$f" "$seeds/$(basename "$(dirname "$f")")-$(basename "$f")"; done
  echo "fuzz: $h for $seconds s ($(ls "$seeds" | wc -l) seeds, $(ls "$corpus" | wc -l) corpus files)"
  # -rss_limit_mb: a file that makes a parser allocate more is a finding.
  # -max_len: scene files and meshes beyond 64 KiB add nothing but time.
  # -timeout: one input taking 10 s is a finding (time must stay bounded).
  # Under ASan, 64 bit: ASan's shadow memory needs -rss_limit_mb, not ulimit -v.
  # A harness's dictionary (tests/fuzz/<harness>.dict), when it has one: libFuzzer
  # refuses to start on a -dict that does not exist (the shard harness had none).
  dict=()
  [ -f "$repo/tests/fuzz/$h.dict" ] && dict=(-dict="$repo/tests/fuzz/$h.dict")
  set +e
  ASAN_OPTIONS="detect_leaks=1:allocator_may_return_null=0" UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1" \
  LSAN_OPTIONS="suppressions=$repo/tools/dev/lsan-suppressions.txt:print_suppressions=0" \
    "$build/tests/fuzz/fuzz_$h" -max_total_time="$seconds" -rss_limit_mb=2048 -max_len=65536 -timeout=10 \
    "${dict[@]}" -print_final_stats=1 -artifact_prefix="$artifacts/" \
    "$corpus" "$seeds" >"$build/fuzz-logs/$h.log" 2>&1
  status=$?
  set -e
  grep -aE '^(#[0-9]+[[:space:]]+(INITED|DONE)|stat::|Done )' "$build/fuzz-logs/$h.log" | sed "s/^/fuzz: $h: /" || true
  kept=0
  for a in "$artifacts"/*; do
    [ -e "$a" ] || continue
    mkdir -p "$repo/tests/hostile/fuzz-regressions/$h"
    cp "$a" "$repo/tests/hostile/fuzz-regressions/$h/"
    echo "fuzz: $h: FOUND $(basename "$a") -> tests/hostile/fuzz-regressions/$h/ (log: $build/fuzz-logs/$h.log)"
    kept=1
  done
  if [ "$status" -ne 0 ] && [ "$kept" -eq 0 ]; then
    echo "fuzz: $h exited with status $status; see $build/fuzz-logs/$h.log" >&2
  fi
  [ "$status" -eq 0 ] && [ "$kept" -eq 0 ] || found=1
done
exit "$found"
