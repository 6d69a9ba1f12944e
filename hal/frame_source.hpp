// One camera's stream of checked frames, as the V4L2 and libcamera backends
// deliver it; the stereo assembly (hal/stereo_assembler.hpp) pairs two of them.
#pragma once

#include "algo/core/result.hpp"
#include "hal/video_frame.hpp"

namespace petra::hal {

class FrameSource {
 public:
  virtual ~FrameSource() = default;
  // The next checked frame within timeout_ms; its data stays valid until the
  // next call. Errors: Errc::timeout, Errc::io_error (device lost or stopped),
  // Errc::parse_error (a broken frame, health().last_fault says which).
  virtual Result<RawFrame> next(int timeout_ms) = 0;
  // Drops every frame already waiting (stale), starting a new sequence run.
  virtual Result<int> flush() = 0;
  virtual const FrameFormat& format() const = 0;
  virtual const CameraHealth& health() const = 0;
};

}  // namespace petra::hal
