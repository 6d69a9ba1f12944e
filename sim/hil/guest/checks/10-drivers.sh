# The drivers themselves, through the distribution's tools: if one of these fails,
# the bench is broken, not the project.

drivers_vcan() {
  timeout 5 candump -n 1 -L vcan0 > /tmp/candump.out 2>&1 &
  local pid=$!
  sleep 0.3
  cansend vcan0 123#DEADBEEF
  wait $pid
  grep -q '123#DEADBEEF' /tmp/candump.out
}
hil_check drivers/vcan drivers_vcan

drivers_gpio() {
  [ -n "$GPIO_CHIP" ] || { echo "no gpio-sim chip"; return 1; }
  gpioinfo "$GPIO_CHIP"
  # the e-stop line follows the simulated pull
  echo pull-down > "$GPIO_SIM/sim_gpio2/pull"
  v=$(gpioget "$GPIO_CHIP" 2); echo "pull-down: gpioget $v"; [ "$v" = 0 ] || return 1
  echo pull-up > "$GPIO_SIM/sim_gpio2/pull"
  v=$(gpioget "$GPIO_CHIP" 2); echo "pull-up: gpioget $v"; [ "$v" = 1 ] || return 1
  # an output is seen on the simulated side while it is held (gpio-sim resets released
  # lines); wait for gpioset to take the line (seconds on a loaded host)
  gpioset --mode=signal "$GPIO_CHIP" 1=1 &
  local pid=$! i=0
  v=0
  while [ $i -lt 50 ] && [ "$v" != 1 ]; do
    sleep 0.1; v=$(cat "$GPIO_SIM/sim_gpio1/value"); i=$((i + 1))
  done
  echo "gpioset 1=1: sim value $v after $i polls"
  kill $pid; wait $pid 2> /dev/null
  [ "$v" = 1 ]
}
hil_check drivers/gpio-sim drivers_gpio

drivers_vivid() {
  local dev
  for v in /sys/class/video4linux/video*; do
    [ "$(cat "$v/name")" = vivid-000-vid-cap ] && dev=/dev/$(basename "$v")
  done
  [ -n "$dev" ] || { echo "no vivid-000-vid-cap"; return 1; }
  v4l2-ctl -d "$dev" --set-fmt-video=width=640,height=480,pixelformat=GREY \
    --stream-mmap --stream-count=2 --stream-to=/tmp/vivid.raw || return 1
  [ "$(stat -c %s /tmp/vivid.raw)" -eq $((2 * 640 * 480)) ]
}
hil_check drivers/vivid drivers_vivid

drivers_vimc() {
  LIBCAMERA_LOG_LEVELS='*:ERROR' timeout 30 cam -l || return 1
  LIBCAMERA_LOG_LEVELS='*:ERROR' timeout 30 cam -c 1 --capture=3 > /tmp/cam.out 2>&1
  cat /tmp/cam.out
  [ "$(grep -c 'seq: ' /tmp/cam.out)" -ge 3 ]
}
hil_check drivers/vimc-libcamera drivers_vimc
