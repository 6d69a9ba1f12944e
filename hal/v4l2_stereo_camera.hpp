// A stereo pair from V4L2 devices: two cameras, or one camera carrying both
// views (layouts and timing: hal/stereo_assembler.hpp), behind the executive's
// StereoCamera interface. open() opens and starts the captures (all buffers
// mapped there); acquire() allocates nothing. FrameMeta times are
// CLOCK_REALTIME (the drivers' monotonic stamps moved by the clocks' offset at
// acquisition); last_info() has the monotonic stamps and driver counters.
#pragma once

#include "hal/stereo_assembler.hpp"
#include "hal/stereo_camera.hpp"
#include "hal/v4l2_capture.hpp"

namespace petra::hal {

struct V4l2StereoConfig {
  StereoTiming timing;
  // Device, formats, buffers and rate of each camera; their width and height
  // are set by open() from the view size and the layout. `right` is used by
  // the two_devices layout only.
  V4l2CaptureConfig left;
  V4l2CaptureConfig right;
};

class V4l2StereoCamera final : public StereoCamera {
 public:
  Status open(const V4l2StereoConfig& config);
  void close();
  int width() const override { return config_.timing.width; }
  int height() const override { return config_.timing.height; }
  const char* name() const override { return "v4l2"; }

  // Takes the next pair into left and right (both width() x height()).
  Result<FrameMeta> acquire(Gray8View left, Gray8View right) override;
  const StereoFrameInfo& last_info() const { return last_; }

  const StereoHealth& health() const { return health_; }
  const V4l2Capture& left_capture() const { return left_; }
  const V4l2Capture& right_capture() const { return right_; }

 private:
  V4l2StereoConfig config_{};
  V4l2Capture left_;
  V4l2Capture right_;
  StereoHealth health_;
  StereoFrameInfo last_{};
  std::uint32_t sequence_ = 0;
};

}  // namespace petra::hal
