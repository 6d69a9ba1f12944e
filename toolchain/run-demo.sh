#!/usr/bin/env bash
# The README's main job: install what is missing, build `release`, run the demo.
set -euo pipefail
cd "$(dirname "$0")/.."
bash toolchain/install-deps.sh build
cmake --preset release -DPETRA_BUILD_TESTS=OFF -DPETRA_BUILD_BENCH=OFF >/dev/null
# The compiler's output goes to a log (GCC 12 prints false-positive -O3
# warnings from Eigen and libstdc++ headers); a failed build shows its tail.
log=build/release/build-demo.log
echo "building petra and petra-fsw (release; about 10 minutes on 2 cores the first time; log: $log)"
if ! cmake --build build/release --target petra petra-fsw >"$log" 2>&1; then
  tail -n 60 "$log"
  echo "build failed; full log: $log" >&2
  exit 1
fi
exec build/release/sim/petra demo "$@"
