#include "fsw/flight_devices.hpp"

#include <cstdio>

namespace petra::fsw {

namespace {

Status name_line(const Status& s, const char* what, const hal::GpioLineConfig& line) {
  if (s) return s;
  return Error::make(s.code(), "gpio.%s (%s line %s): %s", what, line.chip.data(), line.line.data(),
                     s.error().message);
}

}  // namespace

Status FlightDevices::open(const FswConfig& config) {
  kind_ = config.camera_kind;
  const hal::GpioSection& gpio = config.gpio;
  // Power first, off: the drives must not come up before the master is ready to boot them.
  if (gpio.has_arm_power) {
    PETRA_TRY(name_line(arm_power_.open(gpio.arm_power, "petra-fsw", false), "arm_power",
                        gpio.arm_power));
    has_arm_power_ = true;
  }
  if (gpio.has_estop) {
    PETRA_TRY(name_line(estop_line_.open(gpio.estop, "petra-fsw"), "estop", gpio.estop));
    has_estop_ = true;
  }
  if (kind_ == CameraKind::file) {
    PETRA_TRY(file_camera_.open(config.camera_dir.data()));
    (void)std::snprintf(camera_text_, sizeof camera_text_, "file %.180s (%dx%d)",
                        config.camera_dir.data(), file_camera_.width(), file_camera_.height());
    return ok_status();
  }
  if (kind_ == CameraKind::libcamera) return open_libcamera(config);
  hal::V4l2StereoConfig v4l2 = config.v4l2.config;
  if (config.v4l2.triggered) {
    // The cameras expose on the trigger's rising edge: the line idles inactive.
    PETRA_TRY(name_line(trigger_.open(gpio.trigger, "petra-fsw", false), "trigger", gpio.trigger));
    v4l2.timing.trigger = &trigger_;
  }
  if (const Status s = v4l2_camera_.open(v4l2); !s)
    return Error::make(
        s.code(), "camera (v4l2 %s%s%s): %s", v4l2.left.device.data(),
        v4l2.timing.layout == hal::StereoLayout::two_devices ? " + " : "",
        v4l2.timing.layout == hal::StereoLayout::two_devices ? v4l2.right.device.data() : "",
        s.error().message);
  (void)std::snprintf(
      camera_text_, sizeof camera_text_, "v4l2 %.90s%s%.90s (%dx%d%s)", v4l2.left.device.data(),
      v4l2.timing.layout == hal::StereoLayout::two_devices ? " + " : "",
      v4l2.timing.layout == hal::StereoLayout::two_devices ? v4l2.right.device.data() : "",
      v4l2_camera_.width(), v4l2_camera_.height(), config.v4l2.triggered ? ", triggered" : "");
  return ok_status();
}

Status FlightDevices::open_libcamera(const FswConfig& config) {
  hal::LibcameraStereoConfig lc = config.libcamera.config;
  const bool two = lc.timing.layout == hal::StereoLayout::two_devices;
  if (config.libcamera.triggered) {
    PETRA_TRY(name_line(trigger_.open(config.gpio.trigger, "petra-fsw", false), "trigger",
                        config.gpio.trigger));
    lc.timing.trigger = &trigger_;
  }
  if (const Status s = libcamera_camera_.open(lc); !s)
    return Error::make(s.code(), "camera (libcamera %s%s%s): %s", lc.left.camera.data(),
                       two ? " + " : "", two ? lc.right.camera.data() : "", s.error().message);
  (void)std::snprintf(camera_text_, sizeof camera_text_, "libcamera %.90s%s%.90s (%dx%d%s)",
                      lc.left.camera.data(), two ? " + " : "", two ? lc.right.camera.data() : "",
                      libcamera_camera_.width(), libcamera_camera_.height(),
                      config.libcamera.triggered ? ", triggered" : "");
  return ok_status();
}

void FlightDevices::close() {
  if (has_arm_power_) (void)arm_power_.set(false);
  v4l2_camera_.close();
  libcamera_camera_.close();
  trigger_.close();
  arm_power_.close();
  estop_line_.close();
  has_estop_ = false;
  has_arm_power_ = false;
}

hal::StereoCamera& FlightDevices::camera() {
  if (kind_ == CameraKind::v4l2) return v4l2_camera_;
  if (kind_ == CameraKind::libcamera) return libcamera_camera_;
  return file_camera_;
}

Status FlightDevices::power_arm(bool on) {
  if (!has_arm_power_) return ok_status();
  if (const Status s = arm_power_.set(on); !s)
    return Error::make(s.code(), "gpio.arm_power: %s", s.error().message);
  return ok_status();
}

}  // namespace petra::fsw
