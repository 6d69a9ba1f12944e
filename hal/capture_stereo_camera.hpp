// A stereo pair made of one backend's captures (V4L2 or libcamera: the backend
// headers hal/v4l2_stereo_camera.hpp and hal/libcamera_stereo_camera.hpp name
// the instances): two cameras, or one camera carrying both views (layouts and
// timing: hal/stereo_assembler.hpp), behind the executive's StereoCamera
// interface. open() opens and starts the captures (all buffers mapped there);
// acquire() allocates nothing on Petra's side. FrameMeta times are
// CLOCK_REALTIME (the drivers' monotonic stamps moved by the clocks' offset at
// acquisition); last_info() has the monotonic stamps and driver counters.
#pragma once

#include <cstdint>

#include "hal/stereo_assembler.hpp"
#include "hal/stereo_camera.hpp"

namespace petra::hal {

template <class CaptureConfig>
struct CaptureStereoConfig {
  StereoTiming timing;
  // Each camera's capture settings; their width and height are set by open()
  // from the view size and the layout. `right` is used by the two_devices
  // layout only.
  CaptureConfig left;
  CaptureConfig right;
};

// Backend: `Capture` (a FrameSource with open(CaptureConfig), start(), close(),
// is_open()), its `CaptureConfig` (width, height, formats, gaps_are_faults),
// `kName` (the camera's name()) and `kTwoByteFormats` (the 2-byte formats it
// offers, named in the pixel_interleaved refusal).
template <class Backend>
class CaptureStereoCamera final : public StereoCamera {
 public:
  using Capture = typename Backend::Capture;
  using Config = CaptureStereoConfig<typename Backend::CaptureConfig>;

  Status open(const Config& config);
  void close();
  int width() const override { return config_.timing.width; }
  int height() const override { return config_.timing.height; }
  const char* name() const override { return Backend::kName; }

  // Takes the next pair into left and right (both width() x height()).
  Result<FrameMeta> acquire(Gray8View left, Gray8View right) override;
  const StereoFrameInfo& last_info() const { return last_; }

  const StereoHealth& health() const { return health_; }
  const Capture& left_capture() const { return left_; }
  const Capture& right_capture() const { return right_; }

 private:
  Status open_captures(const Config& config);

  Config config_{};
  Capture left_;
  Capture right_;
  StereoHealth health_;
  StereoFrameInfo last_{};
  std::uint32_t sequence_ = 0;
};

}  // namespace petra::hal
