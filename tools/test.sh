#!/usr/bin/env bash
# README command 2: set up, build, and run the whole test suite.
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$repo/tools/setup.sh" test
cd "${PT_BUILD_DIR:-$repo/build}"
ctest --output-on-failure -j "$(nproc 2>/dev/null || echo 2)" "$@"
