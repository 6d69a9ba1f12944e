#!/usr/bin/env bash
# sim/hil/setup.sh: prepare everything the HIL guest needs, once, under a cache directory.
#   - host packages from toolchain/packages-hil.txt (qemu, busybox, tools copied into the guest)
#   - the guest kernel: Debian's linux-image-<abi>-amd64, downloaded with apt and unpacked
#     (dpkg -x), never installed on the host
#   - gpio-sim and vimc, which Debian's 6.1 config leaves out, built out of tree from the
#     linux-source-6.1 package against linux-headers-<abi>
#   - udev (unpacked only): libcamera enumerates only devices that udev has initialised
# Idempotent: a second run with everything in place takes a second.
# Cache: $PETRA_HIL_DIR (default /var/cache/petra-hil), one sub-directory per kernel ABI.
set -euo pipefail
export LC_ALL=C   # byte-wise grep on the kernel image
here=$(cd "$(dirname "$0")" && pwd)
repo=$(cd "$here/../.." && pwd)
cache=${PETRA_HIL_DIR:-/var/cache/petra-hil}
mkdir -p "$cache"
export DEBIAN_FRONTEND=noninteractive
SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO=sudo

say() { echo "hil-setup: $*"; }
# apt-get download with retries: a mirror's hiccup should not fail the test command.
fetch() {
  local i
  for i in 1 2 3; do
    apt-get download -q "$@" && return 0
    say "download of $* failed (try $i of 3)"
    sleep $((i * 5))
  done
  return 1
}

# --- host packages ---------------------------------------------------------------
mapfile -t wanted < <(grep -v '^#' "$repo/toolchain/packages-hil.txt" | sed '/^$/d')
installed=$(dpkg-query -W -f='${Package} ${Status}\n' "${wanted[@]}" 2>/dev/null |
  awk '/ install ok installed$/ {print $1}')
missing=()
for p in "${wanted[@]}"; do
  grep -qx "$p" <<< "$installed" || missing+=("$p")
done
# The guest ABI is whatever linux-image-amd64 points at; an empty answer means no package
# lists. apt-cache takes seconds on a busy machine: the answer is kept until the lists change.
kernel_pkg() {
  local stamp
  stamp=$(stat -c %Y /var/lib/apt/lists 2>/dev/null || echo 0)
  if [ -f "$cache/kernel.env" ] && grep -qx "stamp=$stamp" "$cache/kernel.env"; then
    sed -n 's/^pkg=//p' "$cache/kernel.env"
    return
  fi
  local pkg
  pkg=$(apt-cache depends linux-image-amd64 2>/dev/null |
    awk '/Depends: linux-image-[0-9]/ {print $2; exit}')
  [ -n "$pkg" ] && printf 'stamp=%s\npkg=%s\n' "$stamp" "$pkg" > "$cache/kernel.env"
  echo "$pkg"
}
if [ "${#missing[@]}" -gt 0 ] || [ -z "$(kernel_pkg)" ]; then
  $SUDO apt-get update -qq
fi
if [ "${#missing[@]}" -gt 0 ]; then
  say "installing ${missing[*]}"
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
kpkg=$(kernel_pkg)
[ -n "$kpkg" ] || { say "cannot resolve linux-image-amd64 (apt lists?)"; exit 2; }
kver=${kpkg#linux-image-}
# The headers must match the image exactly (modules carry the ABI in vermagic).
if ! dpkg-query -W -f='${Status}' "linux-headers-$kver" 2>/dev/null | grep -q "install ok installed"; then
  say "installing linux-headers-$kver"
  $SUDO apt-get install -y -qq --no-install-recommends "linux-headers-$kver" >/dev/null
fi

dir=$cache/$kver
mkdir -p "$dir/dl"
cd "$dir"

# --- guest kernel image (unpacked, not installed) ------------------------------
if [ ! -f kroot/boot/vmlinuz-"$kver" ]; then
  say "fetching $kpkg"
  (cd dl && fetch "$kpkg")
  rm -rf kroot
  dpkg -x dl/"${kpkg}"_*.deb kroot
fi
for opt in CONFIG_CAN_VCAN=m CONFIG_VIDEO_VIVID=m CONFIG_CONFIGFS_FS=m CONFIG_PVH=y; do
  grep -q "^$opt" kroot/boot/config-"$kver" || { say "kernel config lacks $opt"; exit 2; }
done
# Uncompressed vmlinux: qemu boots it through its PVH note, skipping the decompressor (~3 s
# under TCG). Debian 6.1 bzImages carry an XZ payload.
if [ ! -f vmlinux ]; then
  # (awk and process substitution rather than head/pipes: no SIGPIPE under pipefail)
  off=$(grep -obUaP '\xfd7zXZ\x00' kroot/boot/vmlinuz-"$kver" | awk -F: 'NR == 1 {print $1}')
  [ -n "$off" ] || { say "no XZ payload in vmlinuz-$kver"; exit 2; }
  xz -dc --single-stream < <(tail -c +"$((off + 1))" kroot/boot/vmlinuz-"$kver") > vmlinux.tmp
  mv vmlinux.tmp vmlinux
fi

# --- out-of-tree gpio-sim and vimc ------------------------------------------------
srcv=$(echo "$kver" | cut -d. -f1,2)
src=linux-source-$srcv
if [ ! -f "$src/drivers/gpio/gpio-sim.c" ] || [ ! -f "$src/drivers/media/test-drivers/vimc/vimc-core.c" ]; then
  say "fetching linux-source-$srcv (only gpio-sim, irq_sim and vimc are extracted)"
  (cd dl && { ls linux-source-"${srcv}"_*.deb >/dev/null 2>&1 || fetch "linux-source-$srcv"; })
  rm -rf srcdeb
  dpkg -x dl/linux-source-"${srcv}"_*.deb srcdeb
  tar -xJf srcdeb/usr/src/"$src".tar.xz --wildcards \
    "$src/drivers/gpio/gpio-sim.c" "$src/drivers/gpio/gpiolib.h" "$src/kernel/irq/irq_sim.c" \
    "$src/drivers/media/test-drivers/vimc/*"
  rm -rf srcdeb dl/linux-source-*.deb   # 150 MB we never need again
fi
build_module() {  # build_module NAME  (sources already in oot/NAME)
  make -s -C /usr/src/linux-headers-"$kver" M="$dir/oot/$1" modules >"$dir/oot/$1.log" 2>&1 ||
    { cat "$dir/oot/$1.log"; say "building $1.ko failed"; exit 2; }
}
if [ ! -f oot/gpio-sim/gpio-sim.ko ]; then
  say "building gpio-sim.ko"
  rm -rf oot/gpio-sim; mkdir -p oot/gpio-sim
  cp "$src/drivers/gpio/gpio-sim.c" oot/gpio-sim/gpio-sim-main.c
  cp "$src/drivers/gpio/gpiolib.h" "$src/kernel/irq/irq_sim.c" oot/gpio-sim/
  # gpio-sim selects IRQ_SIM, which Debian does not build: link irq_sim.c into the module.
  # irq_to_desc() is not exported to modules; generic_handle_irq() reaches the same
  # handle_simple_irq() through the descriptor.
  sed -i 's|handle_simple_irq(irq_to_desc(irqnum));|generic_handle_irq(irqnum);|' oot/gpio-sim/irq_sim.c
  grep -q 'generic_handle_irq(irqnum);' oot/gpio-sim/irq_sim.c || { say "irq_sim.c patch did not apply"; exit 2; }
  printf 'obj-m += gpio-sim.o\ngpio-sim-y := gpio-sim-main.o irq_sim.o\n' > oot/gpio-sim/Kbuild
  build_module gpio-sim
fi
if [ ! -f oot/vimc/vimc.ko ]; then
  say "building vimc.ko"
  rm -rf oot/vimc; mkdir -p oot/vimc
  cp "$src"/drivers/media/test-drivers/vimc/*.[ch] oot/vimc/
  objs=$(cd oot/vimc && ls vimc-*.c | sed 's/\.c$/.o/' | tr '\n' ' ')
  printf 'obj-m += vimc.o\nvimc-y := %s\n' "$objs" > oot/vimc/Kbuild
  build_module vimc
fi

# --- udev for the guest (unpacked only) ----------------------------------------
if [ ! -x udevroot/bin/udevadm ]; then
  say "fetching udev (unpacked for the guest only)"
  (cd dl && fetch udev libsystemd-shared)
  rm -rf udevroot
  for d in dl/udev_*.deb dl/libsystemd-shared_*.deb; do dpkg -x "$d" udevroot; done
fi

echo "KVER=$kver" > "$cache/current.env"
say "ready: kernel $kver in $dir"
