#!/bin/sh
# ctest entry of the ground station browser test (tests/sim/gnd/e2e_gnd.mjs).
#   run_gnd_e2e.sh setup BUILD_DIR                  npm ci (pinned) into BUILD_DIR/gnd
#   run_gnd_e2e.sh run PETRA PETRA_FSW BUILD_DIR     the test itself
# Exit 77 (ctest SKIP_RETURN_CODE) with the reason when node, npm or
# chromium are missing: the test is then reported skipped, never passed.
set -u
here=$(cd "$(dirname "$0")" && pwd)
src=$(cd "$here/../../.." && pwd)
skip() { echo "SKIPPED: $*"; exit 77; }
command -v node >/dev/null 2>&1 || skip "node not installed"
case "$1" in
  setup)
    command -v npm >/dev/null 2>&1 || skip "npm not installed"
    # Re-install only when the lockfile changed (the test stays fast).
    if cmp -s "$src/sim/gnd/package-lock.json" "$2/gnd/package-lock.json" &&
       [ -f "$2/gnd/vendor/three/build/three.module.js" ] &&
       [ -d "$2/gnd/node_modules/playwright-core" ]; then
      echo "npm packages up to date in $2/gnd"; exit 0
    fi
    exec "$src/sim/gnd/install-web.sh" "$2/gnd" ;;
  run)
    [ -x /usr/bin/chromium ] || skip "/usr/bin/chromium not installed (toolchain/packages-test.txt)"
    [ -d "$4/gnd/node_modules/playwright-core" ] || skip "playwright-core not installed (npm ci failed?)"
    exec node "$here/e2e_gnd.mjs" "$2" "$3" "$4" ;;
esac
echo "usage: run_gnd_e2e.sh setup BUILD_DIR | run PETRA PETRA_FSW BUILD_DIR"; exit 2
