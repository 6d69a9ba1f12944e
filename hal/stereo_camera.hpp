// The camera interface of the executive: a synchronized stereo pair of 8-bit
// gray images written into caller buffers, with metadata. Backends: a folder
// of PGM pairs (hal/file_stereo_camera), V4L2 and libcamera (later). An
// implementation allocates only in its constructor/open and reports every
// device problem as an Error naming it.
#pragma once

#include <cstdint>

#include "algo/core/image_view.hpp"
#include "algo/core/result.hpp"

namespace petra::hal {

struct FrameMeta {
  std::uint32_t sequence = 0;      // pairs delivered since open, first is 1
  std::int64_t left_time_ns = 0;   // capture time, CLOCK_REALTIME
  std::int64_t right_time_ns = 0;  // skew = |left - right|, checked by the backend
  std::uint32_t source_index = 0;  // backend-specific (file camera: pair index in the folder)
};

class StereoCamera {
 public:
  virtual ~StereoCamera() = default;
  virtual const char* name() const = 0;
  virtual int width() const = 0;
  virtual int height() const = 0;
  // Takes the next pair into left and right (both width() x height()).
  virtual Result<FrameMeta> acquire(Gray8View left, Gray8View right) = 0;
};

}  // namespace petra::hal
