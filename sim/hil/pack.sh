#!/usr/bin/env bash
# sim/hil/pack.sh BUILD_DIR OUT_DIR: build the guest's initramfs OUT_DIR/initrd.cpio
#   /init and /hil/*        the guest scripts (sim/hil/guest)
#   /usr/lib/modules/...    vcan, gpio-sim, vivid, vimc and their dependencies, in load order
#   /usr/bin/busybox + tools (can-utils, gpiod, v4l2-ctl, media-ctl, cam, udevd)
#   /hil/bin                the project's test programs and binaries from BUILD_DIR
# Host binaries run unchanged in the guest (same x86-64 Debian userland): each comes with
# the ldd closure of its shared libraries. The archive is left uncompressed: the guest
# kernel unpacks it without spending emulated cycles on decompression.
# Two archives, concatenated (the kernel unpacks one after the other): the base (busybox,
# modules, tools; cached in the setup cache, keyed by this script, the kernel and the
# tools) and the project part (programs from BUILD_DIR and the guest scripts, every run).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
build=$(cd "$1" && pwd)
out=$2
cache=${PETRA_HIL_DIR:-/var/cache/petra-hil}
. "$cache/current.env"  # KVER, written by setup.sh
dir=$cache/$KVER
kroot=$dir/kroot
tools=(/usr/bin/cansend /usr/bin/candump /usr/bin/cangen /usr/sbin/ip
  /usr/bin/gpiodetect /usr/bin/gpioinfo /usr/bin/gpioget /usr/bin/gpioset
  /usr/bin/v4l2-ctl /usr/bin/media-ctl /usr/bin/cam)
key=$( (cat "$0"; echo "$KVER"; ls -lL --time-style=+%s /bin/busybox "${tools[@]}") | sha256sum | cut -c1-16)
base=$dir/base-$key.cpio
base_list=$dir/base-$key.list

new_stage() {  # new_stage DIR: an empty merged-/usr tree
  stage=$1
  rm -rf "$stage"
  mkdir -p "$stage"/{usr/bin,usr/sbin,usr/lib,usr/lib64,proc,sys,dev,tmp,run,etc,hil/bin,hil/checks}
  for d in bin sbin lib lib64; do ln -s usr/$d "$stage/$d"; done
}
in_base() {  # in_base /lib/x/libc.so.6: is that file in the cached base (merged /usr)?
  local p=$1
  case $p in /usr/*) ;; *) p=/usr$p ;; esac
  [ -f "$base_list" ] && grep -qxF ".$p" "$base_list"
}

# --- shared-library closure ---------------------------------------------------------
copy_libs() {  # copy_libs FILE...: the libraries (and the loader) FILE needs
  local f lib
  for f in "$@"; do
    ldd "$f" 2>/dev/null | awk '/=> \//{print $3} /^[ \t]*\/lib64\//{print $1}' |
      while read -r lib; do
        case $lib in "$cache"/*) continue ;; esac  # unpacked-only packages: copied by hand
        in_base "$lib" && continue
        [ -e "$stage$lib" ] || { mkdir -p "$stage$(dirname "$lib")"; cp -L "$lib" "$stage$lib"; }
      done
  done
}
copy_tool() {  # copy_tool PATH...: a host program at the same path, with its libraries
  local f
  for f in "$@"; do
    rm -f "$stage$f"
    mkdir -p "$stage$(dirname "$f")"
    cp -L "$f" "$stage$f"
    copy_libs "$f"
  done
}

build_base() {
# --- busybox --------------------------------------------------------------------
cp /bin/busybox "$stage/usr/bin/busybox"
for a in $(/bin/busybox --list); do
  [ -e "$stage/usr/bin/$a" ] || ln -s busybox "$stage/usr/bin/$a"
done

# --- kernel modules in dependency order ------------------------------------------
mkdir -p "$kroot/lib/modules/$KVER/extra"
cp "$dir/oot/gpio-sim/gpio-sim.ko" "$dir/oot/vimc/vimc.ko" "$kroot/lib/modules/$KVER/extra/"
depmod -b "$kroot" "$KVER"  # Debian's package ships no modules.dep
: > "$stage/etc/modules.load"
for m in can can-raw vcan configfs gpio-sim vivid vimc; do
  modprobe -d "$kroot" -S "$KVER" --show-depends "$m" | awk '$1 == "insmod" {print $2}'
done | awk '!seen[$0]++' | while read -r ko; do
  rel=${ko#"$kroot"/}
  mkdir -p "$stage/usr/$(dirname "$rel")"
  cp "$ko" "$stage/usr/$rel"
  echo "/$rel" >> "$stage/etc/modules.load"
done

# --- tools the checks use -----------------------------------------------------------
copy_tool "${tools[@]}"
ipa=/usr/lib/x86_64-linux-gnu/libcamera
copy_tool "$ipa/ipa_vimc.so" "$ipa/vimc_ipa_proxy"
cp "$ipa/ipa_vimc.so.sign" "$stage$ipa/"
mkdir -p "$stage/usr/share/libcamera/ipa"
cp -r /usr/share/libcamera/ipa/vimc "$stage/usr/share/libcamera/ipa/"
# udevd: libcamera only enumerates devices udev has initialised.
u=$dir/udevroot
mkdir -p "$stage/usr/lib/x86_64-linux-gnu/systemd" "$stage/usr/lib/systemd" "$stage/usr/lib/udev/rules.d"
cp "$u/bin/udevadm" "$stage/usr/bin/udevadm"
ln -sf /usr/bin/udevadm "$stage/usr/lib/systemd/systemd-udevd"
cp "$u"/usr/lib/x86_64-linux-gnu/systemd/libsystemd-shared-*.so "$stage/usr/lib/x86_64-linux-gnu/systemd/"
cp "$u"/lib/udev/rules.d/{50-udev-default,60-persistent-v4l}.rules "$stage/usr/lib/udev/rules.d/"
LD_LIBRARY_PATH=$u/usr/lib/x86_64-linux-gnu/systemd copy_libs "$u/bin/udevadm"
(cd "$stage" && find . -print0 | cpio --null -o -H newc --quiet) > "$base.tmp"
(cd "$stage" && find . ! -type d) > "$base_list.tmp"
rm -f "$dir"/base-*.cpio "$dir"/base-*.list
mv "$base_list.tmp" "$base_list"
mv "$base.tmp" "$base"
rm -rf "$stage"
}
if [ ! -f "$base" ] || [ ! -f "$base_list" ]; then
  new_stage "$out/base"
  build_base
fi

new_stage "$out/stage"

# --- the project's programs ---------------------------------------------------------
# Every hal test program (unit tests run again; device tests run for real here), and the
# flight and ground binaries the system checks drive, when this build has them.
shopt -s nullglob
n=0
for t in "$build"/tests/hal_tests "$build"/tests/hal_*_tests; do
  [ -x "$t" ] && [ -f "$t" ] || continue
  cp "$t" "$stage/hil/bin/"; copy_libs "$t"; n=$((n + 1))
done
for name in petra-fsw petra petra-arm-sim petra-ground; do
  for f in "$build/fsw/$name" "$build/sim/$name" "$build/$name"; do
    if [ -x "$f" ] && [ -f "$f" ]; then cp "$f" "$stage/hil/bin/"; copy_libs "$f"; n=$((n + 1)); break; fi
  done
done
[ "$n" -gt 0 ] || { echo "pack: no test programs under $build/tests (build first)" >&2; exit 2; }

# The system checks' calibrated scene (40-arm.sh): rendered here, natively, because the
# renderer takes minutes under emulation. Kept beside the initramfs until petra changes.
petra_bin=$stage/hil/bin/petra
if [ -x "$petra_bin" ]; then
  scene=$out/scene-seed1
  sum=$(sha256sum < "$petra_bin" | cut -c1-16)
  if [ "$(cat "$scene/petra.sum" 2> /dev/null)" != "$sum" ]; then
    rm -rf "$scene"
    "$petra_bin" sim scene --seed 1 --out "$scene" > "$out/scene.log" 2>&1 ||
      { cat "$out/scene.log" >&2; exit 2; }
    echo "$sum" > "$scene/petra.sum"
  fi
  mkdir -p "$stage/hil/scene"
  cp "$scene"/{left.pgm,right.pgm,calib.json,truth.json} "$stage/hil/scene/"
fi

# --- guest scripts --------------------------------------------------------------------
cp "$here/guest/init.sh" "$stage/init"
cp "$here/guest/lib.sh" "$stage/hil/"
cp "$here"/guest/checks/*.sh "$stage/hil/checks/"
chmod +x "$stage/init" "$stage"/hil/checks/*.sh

# Only what the base lacks (directories are shared: newc extraction keeps them).
# The top-level /bin, /lib... links are the base's already.
(cd "$stage" && find . -mindepth 1 ! -path ./bin ! -path ./sbin ! -path ./lib ! -path ./lib64 -print0 |
  cpio --null -o -H newc --quiet) > "$out/project.cpio"
cat "$base" "$out/project.cpio" > "$out/initrd.cpio"
rm -rf "$stage" "$out/project.cpio"
echo "pack: $n project programs, initrd $(du -h "$out/initrd.cpio" | cut -f1)"
