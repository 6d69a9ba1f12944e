#!/usr/bin/env bash
# The README's main job: install what is missing, build `release`, run the demo.
set -euo pipefail
cd "$(dirname "$0")/.."
bash toolchain/install-deps.sh build
cmake --preset release -DPETRA_BUILD_TESTS=OFF -DPETRA_BUILD_BENCH=OFF >/dev/null
cmake --build build/release --target petra petra-fsw
exec build/release/sim/petra demo "$@"
