// A stereo pair from V4L2: two devices (left and right camera), or one device
// delivering both views side by side (2W x H) or pixel-interleaved (W x H, two
// bytes per pixel: left, right; a Bumblebee2-class camera). Each acquire()
// converts one synchronized pair into the caller's 8-bit gray views.
//   free running: stale frames are flushed, the next frames are paired by
//                 timestamp, reading the older side again (at most
//                 max_pair_frames per side) until |t_left - t_right| <= max_skew.
//   triggered:    the trigger line is pulsed once; the next frame of each
//                 camera must be within max_skew, else the pair is refused.
// Memory: the captures' mmap buffers, set up in open(); acquire() allocates nothing.
#pragma once

#include <cstdint>

#include "hal/gpio.hpp"
#include "hal/v4l2_capture.hpp"

namespace petra::hal {

enum class StereoLayout : std::uint8_t { two_devices, side_by_side, pixel_interleaved };
const char* stereo_layout_name(StereoLayout layout);

struct V4l2StereoConfig {
  StereoLayout layout = StereoLayout::two_devices;
  // Device, formats and buffers of each camera; width/height are set by open()
  // from the per-view size below. `right` is used by two_devices only.
  V4l2CaptureConfig left;
  V4l2CaptureConfig right;
  int width = 0;  // px, one view
  int height = 0;
  int timeout_ms = 1000;       // per frame
  std::int64_t max_skew_us = 1000;
  int max_pair_frames = 8;     // free running: frames read per side to find a pair
  GpioOutput* trigger = nullptr;  // set: triggered mode
  std::uint32_t trigger_width_us = 100;
};

struct StereoFrameInfo {
  std::uint32_t sequence = 0;      // pairs delivered since open, the first is 1
  std::int64_t left_time_ns = 0;   // CLOCK_MONOTONIC
  std::int64_t right_time_ns = 0;
  std::uint32_t left_sequence = 0;   // the drivers' frame counters
  std::uint32_t right_sequence = 0;
  std::uint32_t frames_skipped = 0;  // frames read but not paired (free running)
};

struct StereoHealth {
  std::uint32_t pairs = 0;
  std::uint32_t skew_failures = 0;
  FrameFault last_fault = FrameFault::none;
};

class V4l2StereoCamera {
 public:
  Status open(const V4l2StereoConfig& config);
  void close();
  int width() const { return config_.width; }
  int height() const { return config_.height; }
  const char* name() const { return "v4l2"; }

  // Takes the next pair into left and right (both width() x height()).
  Result<StereoFrameInfo> acquire(Gray8View left, Gray8View right);

  const CameraHealth& left_health() const { return left_.health(); }
  const CameraHealth& right_health() const { return right_.health(); }
  const StereoHealth& health() const { return health_; }
  const V4l2Capture& left_capture() const { return left_; }
  const V4l2Capture& right_capture() const { return right_; }

 private:
  Result<StereoFrameInfo> acquire_one_device(Gray8View left, Gray8View right);
  Result<StereoFrameInfo> acquire_two_devices(Gray8View left, Gray8View right);

  V4l2StereoConfig config_{};
  V4l2Capture left_;
  V4l2Capture right_;
  StereoHealth health_;
  std::uint32_t sequence_ = 0;
};

}  // namespace petra::hal
