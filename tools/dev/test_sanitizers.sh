#!/usr/bin/env bash
# Builds the renderer and the whole test suite with AddressSanitizer and
# UndefinedBehaviorSanitizer (PT_SANITIZE=ON, RelWithDebInfo) in build-asan/
# and runs every test. Any sanitizer report fails the run: UBSan does not
# recover (-fno-sanitize-recover=all), ASan halts on the first error, and
# LeakSanitizer's reports are fatal except the documented ones in
# tools/dev/lsan-suppressions.txt (libraries' own leaks; docs/testing.md).
#
#   tools/dev/test_sanitizers.sh [ctest arguments...]   e.g. -R stability
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
build="${PT_ASAN_BUILD_DIR:-$repo/build-asan}"

# Installs what is missing and builds, as the README's commands do, into build-asan/.
PT_BUILD_DIR="$build" PT_BUILD_TYPE=RelWithDebInfo PT_CMAKE_ARGS="-DPT_SANITIZE=ON" "$repo/tools/setup.sh" test

export ASAN_OPTIONS="halt_on_error=1:detect_leaks=1:check_initialization_order=1:strict_init_order=1:detect_stack_use_after_return=1"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
export LSAN_OPTIONS="suppressions=$repo/tools/dev/lsan-suppressions.txt:print_suppressions=0"
cd "$build"
# study_quick is left out: it renders against wall-clock budgets sized for an
# optimized build (0.4 s for the Cornell box), which an ASan build does not
# reach, so its tables come out empty without any sanitizer report. The tools
# it drives (pt-converge, pt-imgerr) run under the sanitizers in test_study_tools.
ctest --output-on-failure -j "$(nproc 2>/dev/null || echo 2)" -E '^study_quick$' "$@"
