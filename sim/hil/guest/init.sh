#!/bin/sh
# The HIL guest's /init: mount the kernel file systems, load the drivers, build the
# bench's "board" (vcan0, a gpio-sim chip with the rover's lines, vivid cameras, vimc
# for libcamera), run every /hil/checks/*.sh in order, print the summary, power off.
export PATH=/usr/bin:/usr/sbin:/hil/bin
mount -t proc proc /proc
mount -t sysfs sysfs /sys
mount -t devtmpfs devtmpfs /dev
mkdir -p /dev/pts /dev/shm
mount -t devpts devpts /dev/pts
mount -t tmpfs tmpfs /dev/shm
mount -t tmpfs tmpfs /tmp
mount -t tmpfs tmpfs /run
. /hil/lib.sh
: > /tmp/hil.results
echo "HIL boot: kernel $(uname -r), $(nproc) cpus, uptime $(cut -d' ' -f1 /proc/uptime) s"

# --- drivers ---------------------------------------------------------------------
# vivid: four capture-only instances (0 and 1 the stereo pair, 2 the one the hal tests
# disconnect, 3 the one the system checks disconnect under petra-fsw).
while read -r ko; do
  args=
  case $ko in */vivid.ko) args="n_devs=4 node_types=0x1,0x1,0x1,0x1" ;; esac
  insmod "$ko" $args 2> /tmp/insmod.err || grep -q 'File exists' /tmp/insmod.err ||
    echo "insmod $ko: $(cat /tmp/insmod.err)"
done < /etc/modules.load
mount -t configfs configfs /sys/kernel/config

# --- the board -------------------------------------------------------------------------
ip link set lo up  # telecommands and telemetry run over loopback UDP
ip link add vcan0 type vcan && ip link set vcan0 up
# gpio-sim chip "petra-hil": the rover's lines by name, as the configuration names them.
G=/sys/kernel/config/gpio-sim/petra
if mkdir $G && mkdir $G/bank0 && echo 8 > $G/bank0/num_lines && echo petra-hil > $G/bank0/label; then
  n=0
  for line in cam_trigger arm_power estop; do
    mkdir $G/bank0/line$n && echo $line > $G/bank0/line$n/name
    n=$((n + 1))
  done
  echo 1 > $G/live
  GPIO_CHIP=$(cat $G/bank0/chip_name)
  GPIO_SIM=/sys/devices/platform/$(cat $G/dev_name)/$GPIO_CHIP
  echo pull-up > $GPIO_SIM/sim_gpio2/pull  # e-stop loop closed: not pressed
  export GPIO_CHIP GPIO_SIM
fi
# udev: libcamera only sees devices udev has initialised.
/usr/lib/systemd/systemd-udevd --daemon 2> /tmp/udevd.err
# Only the media devices: a full trigger costs ~20 s of emulated time.
udevadm trigger --action=add --subsystem-match=video4linux --subsystem-match=media
udevadm settle -t 20
echo "HIL board: modules $(cut -d' ' -f1 /proc/modules | tr '\n' ' ')"
for v in /sys/class/video4linux/video*; do echo "  $(basename "$v"): $(cat "$v/name")"; done
echo "  gpio: $GPIO_CHIP ($GPIO_SIM)  uptime $(cut -d' ' -f1 /proc/uptime) s"

# --- checks ------------------------------------------------------------------------
export PETRA_CAN_IF=vcan0
export LIBCAMERA_LOG_LEVELS='*:ERROR'  # its INFO/WARN lines would drown the test logs
cd /tmp
# hil.only=NN on the kernel command line (PETRA_HIL_APPEND) runs only checks/NN-*.sh.
only=$(sed -n 's/.*hil\.only=\([^ ]*\).*/\1/p' /proc/cmdline)
for c in /hil/checks/*.sh; do
  case $(basename "$c") in ${only:-*}*) ;; *) continue ;; esac
  echo "=== $(basename "$c" .sh)  (uptime $(cut -d' ' -f1 /proc/uptime) s)"
  . "$c"
done
pass=$(grep -c PASS /tmp/hil.results)
fail=$(grep -c FAIL /tmp/hil.results)
echo "HIL summary: $pass passed, $fail failed, uptime $(cut -d' ' -f1 /proc/uptime) s"
echo "HIL done"
sync
poweroff -f
