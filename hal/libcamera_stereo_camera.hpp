// A stereo pair through libcamera: two cameras, or one carrying both views
// (layouts and timing: hal/stereo_assembler.hpp), behind the executive's
// StereoCamera interface; the libcamera twin of hal/v4l2_stereo_camera.
// open() opens and starts the captures (buffers mapped, requests created
// there); acquire() allocates nothing on Petra's side (libcamera's own
// allocations per frame: docs/hal.md). FrameMeta times are CLOCK_REALTIME.
#pragma once

#include "hal/libcamera_capture.hpp"
#include "hal/stereo_assembler.hpp"
#include "hal/stereo_camera.hpp"

namespace petra::hal {

struct LibcameraStereoConfig {
  StereoTiming timing;
  // Camera, formats and buffers of each camera; width and height are set by
  // open() from the view size and the layout. `right` is used by the
  // two_devices layout only.
  LibcameraCaptureConfig left;
  LibcameraCaptureConfig right;
};

class LibcameraStereoCamera final : public StereoCamera {
 public:
  Status open(const LibcameraStereoConfig& config);
  void close();
  int width() const override { return config_.timing.width; }
  int height() const override { return config_.timing.height; }
  const char* name() const override { return "libcamera"; }

  // Takes the next pair into left and right (both width() x height()).
  Result<FrameMeta> acquire(Gray8View left, Gray8View right) override;
  const StereoFrameInfo& last_info() const { return last_; }
  const StereoHealth& health() const { return health_; }

 private:
  LibcameraStereoConfig config_{};
  LibcameraCapture left_;
  LibcameraCapture right_;
  StereoHealth health_;
  StereoFrameInfo last_{};
  std::uint32_t sequence_ = 0;
};

}  // namespace petra::hal
