#include "hal/capture_stereo_camera.hpp"

#include <ctime>

#include "hal/libcamera_stereo_camera.hpp"
#include "hal/v4l2_stereo_camera.hpp"

namespace petra::hal {

// Opens (does not start) the captures the layout needs, sized for it.
template <class Backend>
Status CaptureStereoCamera<Backend>::open_captures(const Config& config) {
  const StereoTiming& t = config.timing;
  // Free running, frames pass by unread between pairs: gaps are only counted.
  const bool triggered = t.trigger != nullptr;
  typename Backend::CaptureConfig left = config.left;
  left.gaps_are_faults = triggered;
  left.width = t.width;
  left.height = t.height;
  switch (t.layout) {
    case StereoLayout::two_devices: {
      typename Backend::CaptureConfig right = config.right;
      right.gaps_are_faults = triggered;
      right.width = t.width;
      right.height = t.height;
      PETRA_TRY(left_.open(left));
      if (auto s = right_.open(right); !s) {
        left_.close();
        return s;
      }
      break;
    }
    case StereoLayout::side_by_side:
      left.width = 2 * t.width;
      PETRA_TRY(left_.open(left));
      break;
    case StereoLayout::pixel_interleaved: {
      // Two bytes per pixel carry the two views: only a 16-bit container fits.
      FixedVector<PixelFormat, kPixelFormatCount> two_byte;
      for (PixelFormat f : config.left.formats)
        if (bytes_per_pixel(f) == 2) (void)two_byte.push_back(f);
      if (two_byte.empty())
        return Error::make(Errc::invalid_argument,
                           "stereo: pixel_interleaved needs a 2-byte format (%s)",
                           Backend::kTwoByteFormats);
      left.formats = two_byte;
      PETRA_TRY(left_.open(left));
      break;
    }
  }
  return ok_status();
}

template <class Backend>
Status CaptureStereoCamera<Backend>::open(const Config& config) {
  close();
  PETRA_TRY(check_stereo_timing(config.timing));
  config_ = config;
  PETRA_TRY(open_captures(config));
  if (auto s = left_.start(); !s) {
    close();
    return s;
  }
  if (config.timing.layout == StereoLayout::two_devices) {
    if (auto s = right_.start(); !s) {
      close();
      return s;
    }
  }
  return ok_status();
}

template <class Backend>
void CaptureStereoCamera<Backend>::close() {
  left_.close();
  right_.close();
  sequence_ = 0;
}

namespace {

std::int64_t clock_ns(clockid_t id) {
  timespec ts{};
  clock_gettime(id, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

}  // namespace

template <class Backend>
Result<FrameMeta> CaptureStereoCamera<Backend>::acquire(Gray8View left, Gray8View right) {
  if (!left_.is_open()) return Error::make(Errc::not_ready, "stereo: acquire() before open()");
  const bool two = config_.timing.layout == StereoLayout::two_devices;
  auto r = assemble_pair(config_.timing, left_, two ? &right_ : nullptr, left, right, health_);
  if (!r) return r.error();
  r->sequence = ++sequence_;
  last_ = *r;
  // V4L2's and libcamera's completion stamps are both CLOCK_MONOTONIC.
  const std::int64_t offset = clock_ns(CLOCK_REALTIME) - clock_ns(CLOCK_MONOTONIC);
  FrameMeta meta;
  meta.sequence = r->sequence;
  meta.left_time_ns = r->left_time_ns + offset;
  meta.right_time_ns = r->right_time_ns + offset;
  meta.source_index = r->left_sequence;
  return meta;
}

// The backends, compiled once here (their headers declare these extern).
template class CaptureStereoCamera<V4l2StereoBackend>;
template class CaptureStereoCamera<LibcameraStereoBackend>;

}  // namespace petra::hal
