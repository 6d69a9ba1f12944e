#!/usr/bin/env bash
# Builds the libFuzzer target with clang and runs it for SECONDS seconds.
# Usage: tests/fuzz/run_fuzz.sh BUILD_DIR [SECONDS]
# Exit 0 when the fuzzer found nothing; its crash input is kept in BUILD_DIR otherwise.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
build=$1
seconds=${2:-60}
if ! command -v clang++ >/dev/null; then
  echo "run_fuzz: clang++ not installed (toolchain/packages-test.txt lists it)" >&2
  exit 1
fi
cmake -S "$here" -B "$build" -G Ninja -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build "$build" >/dev/null
mkdir -p "$build/corpus"
cd "$build"
./fuzz_command_decoder -max_total_time="$seconds" -max_len=256 -print_final_stats=1 corpus 2>&1 | tail -n 15
