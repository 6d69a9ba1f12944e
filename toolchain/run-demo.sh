#!/usr/bin/env bash
# The README's main job: install what is missing, build `release`, run the demo.
# Its own build directory: turning tests and benchmarks off in build/release
# would leave that directory without the benchmarks docs/performance.md runs.
set -euo pipefail
cd "$(dirname "$0")/.."
bash toolchain/install-deps.sh build
build=build/demo
cmake --preset release -B "$build" -DPETRA_BUILD_TESTS=OFF -DPETRA_BUILD_BENCH=OFF >/dev/null
# The compiler's output goes to a log (GCC 12 prints false-positive -O3
# warnings from Eigen and libstdc++ headers); a failed build shows its tail.
log=$build/build-demo.log
echo "building petra and petra-fsw (release; about 10 minutes on 2 cores the first time; log: $log)"
if ! cmake --build "$build" --target petra petra-fsw >"$log" 2>&1; then
  tail -n 60 "$log"
  echo "build failed; full log: $log" >&2
  exit 1
fi
exec "$build"/sim/petra demo "$@"
