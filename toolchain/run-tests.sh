#!/usr/bin/env bash
# The README's test command: install what is missing, then build and run every
# test: the host `check` build (optimised as flown, -O2 -DNDEBUG, under ASan and
# UBSan with no recovery, warnings as errors; every host test, the fuzz targets'
# bounded campaigns included), the hardware-in-the-loop bench on that build
# (sim/hil: Debian's kernel under qemu with vcan, gpio-sim, vivid and vimc;
# docs/hil.md) and the aarch64 cross build (-O3, unit tests under qemu user
# emulation). Exit non-zero on any failure. PETRA_SKIP_HIL=1 skips the bench
# (reported as skipped).
set -euo pipefail
cd "$(dirname "$0")/.."
start=$(date +%s)
stamp() { echo "== $1 ($(( $(date +%s) - start )) s) =="; }
bash toolchain/install-deps.sh test
jobs=$(nproc)
mkdir -p build

# The bench's first set-up is mostly downloads (~310 MB: the guest kernel and the
# source of two drivers): it runs while the host build compiles. It is cached
# (/var/cache/petra-hil); a later run checks it in a second.
hil_setup=none
if [ "${PETRA_SKIP_HIL:-0}" != 1 ]; then
  cache=${PETRA_HIL_DIR:-/var/cache/petra-hil}
  mkdir -p "$cache"
  flock "$cache/.lock" bash sim/hil/setup.sh > build/hil-setup.log 2>&1 &
  hil_setup=$!
fi

# A sanitizer report fails the test that made it (-fno-sanitize-recover), with
# its stack, symbolized from the -g1 line tables.
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1}

stamp "host build (check: -O2, ASan + UBSan)"
cmake --preset check >/dev/null
cmake --build build/check -j "$jobs"
# The aarch64 cross build runs meanwhile at the lowest CPU priority: it takes
# only what the host tests and the bench leave idle (the bench's guest waits on
# its devices' timers), so neither's timing changes; its log is
# build/aarch64-build.log. It is stopped if the command ends early.
cmake --preset aarch64 >/dev/null
setsid nice -n 19 cmake --build build/aarch64 -j "$jobs" > build/aarch64-build.log 2>&1 &
aarch64_build=$!
trap 'kill -- -"$aarch64_build" 2>/dev/null || true' EXIT

stamp "host tests (check)"
ctest --preset check -j "$jobs" -LE hil
# Each fuzz target's campaign: its number of executions.
grep -h "executions in" build/check/Testing/Temporary/LastTest.log || true

stamp "hardware-in-the-loop bench"
if [ "$hil_setup" != none ] && ! wait "$hil_setup"; then
  tail -30 build/hil-setup.log
  echo "HIL set-up failed (build/hil-setup.log)"
  exit 1
fi
# --verbose: the bench's PASS/FAIL line per check goes to this command's output.
ctest --preset check -L hil --verbose

stamp "aarch64 cross build (finishing), unit tests under qemu-aarch64-static"
if ! wait "$aarch64_build"; then
  tail -40 build/aarch64-build.log
  echo "aarch64 build failed (build/aarch64-build.log)"
  exit 1
fi
trap - EXIT
tail -1 build/aarch64-build.log
ctest --preset aarch64 -j "$jobs"

stamp "all tests passed"
