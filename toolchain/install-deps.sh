#!/usr/bin/env bash
# Installs what Petra needs on Debian 12 (as root), skipping what is present.
# Usage: toolchain/install-deps.sh [build|test|bench]
#   build: compilers, CMake, Eigen, CLI11, libsodium, libpng (enough for the demo)
#   test:  build + GoogleTest, Google Benchmark, the aarch64 cross toolchain and
#          qemu user emulation, the peers/oracles tests use, and the HIL bench's
#          host packages (qemu-system, busybox, kernel headers...: packages-hil.txt).
#   bench: test + OpenCV and hyperfine (the peers benchmarks measure against).
set -euo pipefail
kind=${1:-build}
here=$(cd "$(dirname "$0")" && pwd)

mapfile -t wanted < <(grep -v '^#' "$here/packages-build.txt" | sed '/^$/d')
add_list() { mapfile -t -O "${#wanted[@]}" wanted < <(grep -v '^#' "$here/$1" | sed '/^$/d'); }
case "$kind" in
  build) ;;
  test) add_list packages-test.txt; add_list packages-hil.txt ;;
  bench) add_list packages-test.txt; add_list packages-hil.txt; add_list packages-bench.txt ;;
  *) echo "install-deps: unknown kind '$kind' (build|test|bench)" >&2; exit 2 ;;
esac

# Names that installed packages provide count as present (e.g. npm inside a
# Node.js package that conflicts with Debian's npm): never replace them.
provided=$(dpkg-query -W -f='${db:Status-Abbrev}|${Provides}\n' 2>/dev/null |
  sed -n 's/^ii *|//p' | tr ',' '\n' | sed 's/([^)]*)//; s/ //g' | sort -u)
missing=()
for p in "${wanted[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" ||
    grep -qxF "$p" <<<"$provided" || missing+=("$p")
done
if [ "${#missing[@]}" -eq 0 ]; then
  echo "install-deps: all ${#wanted[@]} packages present"
  exit 0
fi
echo "install-deps: installing ${missing[*]}"
SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO=sudo
export DEBIAN_FRONTEND=noninteractive
# Multiarch packages (name:arm64) need their architecture enabled first.
if printf '%s\n' "${missing[@]}" | grep -q ':arm64$' && ! dpkg --print-foreign-architectures | grep -qx arm64; then
  $SUDO dpkg --add-architecture arm64
fi
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "install-deps: done"
