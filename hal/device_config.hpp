// The device sections of the flight configuration, parsed into the hal
// backends' configurations (format in docs/hal.md "Device configuration"):
//   "camera": {"kind": "v4l2", "layout": "two_devices", "left": "vivid-000-vid-cap",
//              "right": "vivid-001-vid-cap", "width": 640, "height": 480,
//              "formats": ["GREY", "YUYV"], "buffers": 4, "fps": 25, "timeout_ms": 1000,
//              "max_skew_us": 20000, "max_pair_frames": 8, "triggered": false,
//              "trigger_width_us": 100}
//   "gpio": {"chip": "petra-hil", "trigger": "cam_trigger", "arm_power": "arm_power",
//            "estop": {"line": "estop", "active_low": true}}
// A gpio line is a line name on the section's chip, or an object with its own
// "chip", "line" and "active_low". Errors name the field ("camera.fps: ...").
// "kind": "libcamera" takes the same fields but "fps" (parse_libcamera_camera).
// Init only (heap-free, but not meant for the loop).
#pragma once

#include "algo/core/json_reader.hpp"
#include "hal/gpio.hpp"
#include "hal/libcamera_stereo_camera.hpp"
#include "hal/v4l2_stereo_camera.hpp"

namespace petra::hal {

// `obj` is the camera object; its "kind" is not checked here (the caller
// dispatches on it). "triggered": true means the caller must set
// timing.trigger to the trigger line before open().
struct V4l2CameraSection {
  V4l2StereoConfig config;
  bool triggered = false;
};
Result<V4l2CameraSection> parse_v4l2_camera(const json::Document& doc, std::uint32_t obj);

// The same fields for "kind": "libcamera", except that "left" and "right" are
// substrings of libcamera camera ids ("Sensor B"), there is no "fps", and Y16
// is refused (libcamera has no 16-bit gray).
struct LibcameraCameraSection {
  LibcameraStereoConfig config;
  bool triggered = false;
};
Result<LibcameraCameraSection> parse_libcamera_camera(const json::Document& doc, std::uint32_t obj);

struct GpioSection {
  GpioLineConfig trigger;
  GpioLineConfig arm_power;
  GpioLineConfig estop;
  bool has_trigger = false;  // each line is optional: absent = not wired
  bool has_arm_power = false;
  bool has_estop = false;
};
Result<GpioSection> parse_gpio(const json::Document& doc, std::uint32_t obj);

}  // namespace petra::hal
