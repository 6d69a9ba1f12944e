#!/usr/bin/env bash
# The README's test command: install what is missing, then build and run every
# test: the host `dev` build (all tests, warnings as errors) and the aarch64
# cross build (unit tests under qemu user emulation). Exit non-zero on failure.
set -euo pipefail
cd "$(dirname "$0")/.."
start=$(date +%s)
bash toolchain/install-deps.sh test
jobs=$(nproc)

echo "== host build (dev) =="
cmake --preset dev >/dev/null
cmake --build build/dev -j "$jobs"
# The HIL bench (label "hil", sim/hil/run.sh, docs/hil.md) is not part of this
# command yet: its whole-system checks are unfinished (issue 10). Run it with
#   ctest --test-dir build/dev -L hil    or    bash sim/hil/run.sh --build build/dev
ctest --preset dev -j "$jobs" -LE hil

echo "== aarch64 cross build, unit tests under qemu-aarch64-static =="
cmake --preset aarch64 >/dev/null
cmake --build build/aarch64 -j "$jobs"
ctest --preset aarch64 -j "$jobs"

echo "== all tests passed in $(( $(date +%s) - start )) s =="
