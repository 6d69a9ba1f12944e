#!/usr/bin/env bash
# The hardware-in-the-loop bench, one command (root on Debian 12; docs/hil.md):
#
#   bash sim/hil/run.sh [--build DIR] [--out DIR]
#
# 1. setup.sh  host packages, guest kernel, gpio-sim and vimc modules (cached; ~1 s when done)
# 2. pack.sh   initramfs with the drivers, tools and the project's programs from DIR
#              (default build/dev; build it first)
# 3. boot Debian's kernel under qemu (TCG: no KVM needed) with the initramfs; the guest
#    builds the board (vcan0, gpio-sim chip "petra-hil", vivid x4, vimc), runs
#    sim/hil/guest/checks/*.sh and powers off
# 4. print every "HIL <check> PASS|FAIL" line as it comes; exit 0 only when the guest
#    finished ("HIL done"), at least one check ran and none failed.
# PETRA_SKIP_HIL=1 skips the bench (exit 77, shown by ctest as skipped).
# PETRA_HIL_DIR: cache (default /var/cache/petra-hil); PETRA_HIL_TIMEOUT: seconds (600).
set -uo pipefail
here=$(cd "$(dirname "$0")" && pwd)
repo=$(cd "$here/../.." && pwd)
build=$repo/build/dev
out=
while [ $# -gt 0 ]; do
  case $1 in
    --build) build=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    *) echo "usage: $0 [--build DIR] [--out DIR]" >&2; exit 2 ;;
  esac
done
out=${out:-$build/hil}
if [ "${PETRA_SKIP_HIL:-0}" = 1 ]; then
  echo "HIL bench skipped (PETRA_SKIP_HIL=1)"
  exit 77
fi
[ -d "$build/tests" ] || { echo "hil: no build in $build (cmake --preset dev && cmake --build build/dev)"; exit 2; }
mkdir -p "$out"
cache=${PETRA_HIL_DIR:-/var/cache/petra-hil}
mkdir -p "$cache"
t0=$(date +%s.%N)
elapsed() { awk -v a="$1" -v b="$(date +%s.%N)" 'BEGIN {printf "%.1f", b - a}'; }

# Several checkouts may run the bench at once: the shared cache is prepared under a lock.
flock "$cache/.lock" bash "$here/setup.sh" > "$out/setup.log" 2>&1 || { tail -20 "$out/setup.log"; echo "hil: setup failed ($out/setup.log)"; exit 2; }
t_setup=$(elapsed "$t0")
t1=$(date +%s.%N)
flock "$cache/.lock" bash "$here/pack.sh" "$build" "$out" > "$out/pack.log" 2>&1 || { tail -20 "$out/pack.log"; echo "hil: packing failed ($out/pack.log)"; exit 2; }
t_pack=$(elapsed "$t1")
. "$cache/current.env"
kernel=$cache/$KVER/vmlinux
echo "hil: setup ${t_setup} s, pack ${t_pack} s ($(tail -1 "$out/pack.log")); booting $KVER under qemu"

t2=$(date +%s.%N)
# -cpu max: the emulated CPU has every feature TCG offers (the kernel wants x86-64-v1 only).
# The serial console is the guest's stdout; HIL lines are shown live, all of it is kept.
timeout "${PETRA_HIL_TIMEOUT:-600}" qemu-system-x86_64 -accel tcg,thread=multi -cpu max -smp 2 -m 1536 \
  -kernel "$kernel" -initrd "$out/initrd.cpio" \
  -append "console=ttyS0 quiet loglevel=3 panic=-1 ${PETRA_HIL_APPEND:-}" \
  -nographic -no-reboot -nodefaults -serial stdio -monitor none < /dev/null 2>&1 |
  sed -u 's/\r$//' | tee "$out/console.log" | grep --line-buffered -E '^(HIL |  \| )'
qemu_rc=${PIPESTATUS[0]}
t_boot=$(elapsed "$t2")

pass=$(grep -c -E '^HIL [^ ]+ PASS( |$)' "$out/console.log")
fail=$(grep -c -E '^HIL [^ ]+ FAIL( |$)' "$out/console.log")
verdict=0
if ! grep -q '^HIL done' "$out/console.log"; then
  echo "hil: the guest did not finish (qemu exit $qemu_rc; see $out/console.log)"
  tail -20 "$out/console.log"
  verdict=1
fi
[ "$pass" -gt 0 ] || verdict=1
[ "$fail" -eq 0 ] || verdict=1
echo "hil: $pass passed, $fail failed; setup ${t_setup} s, pack ${t_pack} s, guest ${t_boot} s, total $(elapsed "$t0") s"
echo "hil: console log $out/console.log"
exit $verdict
