#!/usr/bin/env bash
# The libFuzzer targets (tests/fuzz/CMakeLists.txt), built with clang.
#   tests/fuzz/run_fuzz.sh build BUILD_DIR            configure and build every target
#   tests/fuzz/run_fuzz.sh run BUILD_DIR TARGET SECONDS [RUNS]
#       one bounded campaign: at most SECONDS seconds (and RUNS executions when
#       given); prints "fuzz TARGET: N executions in S s" and libFuzzer's stats.
# Exit 0 when the fuzzer found nothing; its crash input is kept in BUILD_DIR otherwise.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
what=$1
build=$2
if ! command -v clang++ >/dev/null; then
  echo "run_fuzz: clang++ not installed (toolchain/packages-test.txt lists it)" >&2
  exit 1
fi
case $what in
  build)
    cmake -S "$here" -B "$build" -G Ninja -DCMAKE_CXX_COMPILER=clang++ \
      -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
    cmake --build "$build" > "$build/build.log" 2>&1 || { tail -40 "$build/build.log"; exit 1; }
    ;;
  run)
    target=$3
    seconds=$4
    runs=${5:--1}
    [ -x "$build/$target" ] || { echo "run_fuzz: $build/$target not built (run_fuzz.sh build)" >&2; exit 1; }
    mkdir -p "$build/corpus-$target"
    build=$(cd "$build" && pwd)  # libFuzzer's -artifact_prefix is read after the cd below
    cd "$build"
    start=$(date +%s%N)
    set +e
    ./"$target" -max_total_time="$seconds" -runs="$runs" -max_len=512 -print_final_stats=1 \
      -artifact_prefix="$build/$target-" "corpus-$target" > "$target.log" 2>&1
    rc=$?
    set -e
    ms=$(( ($(date +%s%N) - start) / 1000000 ))
    execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$target.log")
    tail -n 12 "$target.log"
    printf 'fuzz %s: %s executions in %d.%d s%s\n' "$target" "${execs:-?}" $((ms / 1000)) $((ms % 1000 / 100)) \
      "$([ $rc = 0 ] && echo ', no finding' || echo ", FAILED (exit $rc)")"
    exit $rc
    ;;
  *) echo "usage: $0 build BUILD_DIR | run BUILD_DIR TARGET SECONDS [RUNS]" >&2; exit 2 ;;
esac
