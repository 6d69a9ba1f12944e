// A stereo pair through libcamera (hal/capture_stereo_camera.hpp over
// hal/libcamera_capture.hpp), the libcamera twin of hal/v4l2_stereo_camera.
// open() also creates the requests; acquire() allocates nothing on Petra's
// side (libcamera's own allocations per frame: docs/hal.md).
#pragma once

#include "hal/capture_stereo_camera.hpp"
#include "hal/libcamera_capture.hpp"

namespace petra::hal {

struct LibcameraStereoBackend {
  using Capture = LibcameraCapture;
  using CaptureConfig = LibcameraCaptureConfig;
  static constexpr const char* kName = "libcamera";
  static constexpr const char* kTwoByteFormats = "YUYV";  // no 16-bit gray in libcamera
};

// Camera, formats and buffers of each camera, with the stereo timing.
using LibcameraStereoConfig = CaptureStereoConfig<LibcameraCaptureConfig>;
using LibcameraStereoCamera = CaptureStereoCamera<LibcameraStereoBackend>;
extern template class CaptureStereoCamera<LibcameraStereoBackend>;

}  // namespace petra::hal
