// The devices petra-fsw opens from its configuration (docs/hal.md "Wiring in
// petra-fsw"): the stereo camera (a folder of pairs, V4L2 cameras or cameras
// through libcamera) and the
// GPIO lines (e-stop input, arm power enable and camera trigger outputs, each
// optional). open() runs once at init and owns every device; the executive
// gets them through Dependencies. No heap after open().
#pragma once

#include "fsw/config.hpp"
#include "hal/file_stereo_camera.hpp"
#include "hal/gpio_digital_input.hpp"
#include "hal/gpio_gpiod.hpp"
#include "hal/libcamera_stereo_camera.hpp"
#include "hal/v4l2_stereo_camera.hpp"

namespace petra::fsw {

class FlightDevices {
 public:
  FlightDevices() = default;
  FlightDevices(const FlightDevices&) = delete;
  FlightDevices& operator=(const FlightDevices&) = delete;

  // Opens the configured devices; the arm power line is driven inactive
  // (drives unpowered) until power_arm(true). Errors name the device.
  Status open(const FswConfig& config);
  void close();

  hal::StereoCamera& camera();
  hal::DigitalInput* estop() { return has_estop_ ? &estop_ : nullptr; }
  // Switches the arm's drive power; a success when the line is not wired.
  Status power_arm(bool on);
  bool arm_power_wired() const { return has_arm_power_; }
  const char* camera_description() const { return camera_text_; }

 private:
  Status open_libcamera(const FswConfig& config);

  CameraKind kind_ = CameraKind::file;
  hal::FileStereoCamera file_camera_;
  hal::V4l2StereoCamera v4l2_camera_;
  hal::LibcameraStereoCamera libcamera_camera_;
  hal::GpiodOutput trigger_;
  hal::GpiodOutput arm_power_;
  hal::GpiodInput estop_line_;
  hal::GpioDigitalInput estop_{estop_line_};
  bool has_estop_ = false;
  bool has_arm_power_ = false;
  char camera_text_[256] = "";  // for the boot line; long names are cut
};

}  // namespace petra::fsw
