// A stereo pair from V4L2 devices (hal/capture_stereo_camera.hpp over
// hal/v4l2_capture.hpp): two cameras, or one camera carrying both views.
#pragma once

#include "hal/capture_stereo_camera.hpp"
#include "hal/v4l2_capture.hpp"

namespace petra::hal {

struct V4l2StereoBackend {
  using Capture = V4l2Capture;
  using CaptureConfig = V4l2CaptureConfig;
  static constexpr const char* kName = "v4l2";
  static constexpr const char* kTwoByteFormats = "Y16 or YUYV";
};

// Device, formats, buffers and rate of each camera, with the stereo timing.
using V4l2StereoConfig = CaptureStereoConfig<V4l2CaptureConfig>;
using V4l2StereoCamera = CaptureStereoCamera<V4l2StereoBackend>;
extern template class CaptureStereoCamera<V4l2StereoBackend>;

}  // namespace petra::hal
