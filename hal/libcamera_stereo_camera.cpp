#include "hal/libcamera_stereo_camera.hpp"

#include <ctime>

namespace petra::hal {

Status LibcameraStereoCamera::open(const LibcameraStereoConfig& config) {
  close();
  const StereoTiming& t = config.timing;
  PETRA_TRY(check_stereo_timing(t));
  config_ = config;
  // Free running, frames pass by unread between pairs: gaps are only counted.
  const bool triggered = t.trigger != nullptr;
  LibcameraCaptureConfig left = config.left;
  left.gaps_are_faults = triggered;
  left.width = t.width;
  left.height = t.height;
  switch (t.layout) {
    case StereoLayout::two_devices: {
      LibcameraCaptureConfig right = config.right;
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
                           "stereo: pixel_interleaved needs a 2-byte format (YUYV)");
      left.formats = two_byte;
      PETRA_TRY(left_.open(left));
      break;
    }
  }
  if (auto s = left_.start(); !s) {
    close();
    return s;
  }
  if (t.layout == StereoLayout::two_devices) {
    if (auto s = right_.start(); !s) {
      close();
      return s;
    }
  }
  return ok_status();
}

void LibcameraStereoCamera::close() {
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

Result<FrameMeta> LibcameraStereoCamera::acquire(Gray8View left, Gray8View right) {
  if (!left_.is_open()) return Error::make(Errc::not_ready, "stereo: acquire() before open()");
  const bool two = config_.timing.layout == StereoLayout::two_devices;
  auto r = assemble_pair(config_.timing, left_, two ? &right_ : nullptr, left, right, health_);
  if (!r) return r.error();
  r->sequence = ++sequence_;
  last_ = *r;
  // libcamera's completion stamps are CLOCK_MONOTONIC, as V4L2's.
  const std::int64_t offset = clock_ns(CLOCK_REALTIME) - clock_ns(CLOCK_MONOTONIC);
  FrameMeta meta;
  meta.sequence = r->sequence;
  meta.left_time_ns = r->left_time_ns + offset;
  meta.right_time_ns = r->right_time_ns + offset;
  meta.source_index = r->left_sequence;
  return meta;
}

}  // namespace petra::hal
