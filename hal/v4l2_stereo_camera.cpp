#include "hal/v4l2_stereo_camera.hpp"

#include "hal/stereo_pairing.hpp"

namespace petra::hal {

const char* stereo_layout_name(StereoLayout layout) {
  switch (layout) {
    case StereoLayout::two_devices:
      return "two_devices";
    case StereoLayout::side_by_side:
      return "side_by_side";
    case StereoLayout::pixel_interleaved:
      return "pixel_interleaved";
  }
  return "?";
}

Status V4l2StereoCamera::open(const V4l2StereoConfig& config) {
  close();
  if (config.width <= 0 || config.height <= 0)
    return Error::make(Errc::invalid_argument, "stereo: view size %dx%d must be positive",
                       config.width, config.height);
  if (config.timeout_ms <= 0 || config.timeout_ms > 60'000)
    return Error::make(Errc::invalid_argument, "stereo: timeout_ms %d outside 1..60000",
                       config.timeout_ms);
  if (config.max_skew_us < 0 || config.max_skew_us > 1'000'000)
    return Error::make(Errc::invalid_argument, "stereo: max_skew_us %lld outside 0..1000000",
                       static_cast<long long>(config.max_skew_us));
  if (config.max_pair_frames < 1 || config.max_pair_frames > 64)
    return Error::make(Errc::invalid_argument, "stereo: max_pair_frames %d outside 1..64",
                       config.max_pair_frames);
  config_ = config;
  // Free running: frames pass by unread between pairs, so gaps are only counted.
  const bool triggered = config.trigger != nullptr;
  V4l2CaptureConfig left = config.left;
  left.gaps_are_faults = triggered;
  left.width = config.width;
  left.height = config.height;
  switch (config.layout) {
    case StereoLayout::two_devices: {
      V4l2CaptureConfig right = config.right;
      right.gaps_are_faults = triggered;
      right.width = config.width;
      right.height = config.height;
      PETRA_TRY(left_.open(left));
      if (auto s = right_.open(right); !s) {
        left_.close();
        return s;
      }
      break;
    }
    case StereoLayout::side_by_side:
      left.width = 2 * config.width;
      PETRA_TRY(left_.open(left));
      break;
    case StereoLayout::pixel_interleaved: {
      // Two bytes per pixel carry the two views: only a 16-bit container fits.
      FixedVector<PixelFormat, kPixelFormatCount> two_byte;
      for (PixelFormat f : config.left.formats)
        if (bytes_per_pixel(f) == 2) (void)two_byte.push_back(f);
      if (two_byte.empty())
        return Error::make(Errc::invalid_argument,
                           "stereo: pixel_interleaved needs a 2-byte format (Y16 or YUYV)");
      left.formats = two_byte;
      PETRA_TRY(left_.open(left));
      break;
    }
  }
  const bool two = config.layout == StereoLayout::two_devices;
  PETRA_TRY(left_.start());
  if (two) {
    if (auto s = right_.start(); !s) {
      close();
      return s;
    }
  }
  return ok_status();
}

void V4l2StereoCamera::close() {
  left_.close();
  right_.close();
  sequence_ = 0;
}

Result<StereoFrameInfo> V4l2StereoCamera::acquire(Gray8View left, Gray8View right) {
  if (!left_.is_open()) return Error::make(Errc::not_ready, "stereo: acquire() before open()");
  if (left.width() != config_.width || left.height() != config_.height ||
      right.width() != config_.width || right.height() != config_.height)
    return Error::make(Errc::invalid_argument, "stereo: views %dx%d and %dx%d, camera gives %dx%d",
                       left.width(), left.height(), right.width(), right.height(), config_.width,
                       config_.height);
  auto r = config_.layout == StereoLayout::two_devices ? acquire_two_devices(left, right)
                                                       : acquire_one_device(left, right);
  if (r) {
    ++health_.pairs;
    r->sequence = ++sequence_;
  }
  return r;
}

Result<StereoFrameInfo> V4l2StereoCamera::acquire_one_device(Gray8View left, Gray8View right) {
  if (config_.trigger != nullptr) {
    PETRA_TRY(pulse(*config_.trigger, config_.trigger_width_us));
  } else {
    PETRA_TRY(left_.flush());
  }
  auto frame = left_.next(config_.timeout_ms);
  if (!frame) {
    health_.last_fault = left_.health().last_fault;
    return frame.error();
  }
  if (config_.layout == StereoLayout::side_by_side) {
    PETRA_TRY(convert_to_gray(*frame, left_.format(), 0, left));
    PETRA_TRY(convert_to_gray(*frame, left_.format(), config_.width, right));
  } else {
    PETRA_TRY(deinterleave_pair(*frame, left_.format(), left, right));
  }
  StereoFrameInfo info;
  info.left_time_ns = info.right_time_ns = frame->time_ns;
  info.left_sequence = info.right_sequence = frame->sequence;
  return info;
}

Result<StereoFrameInfo> V4l2StereoCamera::acquire_two_devices(Gray8View left, Gray8View right) {
  const bool triggered = config_.trigger != nullptr;
  if (triggered) {
    PETRA_TRY(pulse(*config_.trigger, config_.trigger_width_us));
  } else {
    PETRA_TRY(left_.flush());
    PETRA_TRY(right_.flush());
  }
  auto fail = [this](const Error& e, const V4l2Capture& side) -> Error {
    health_.last_fault = side.health().last_fault;
    return e;
  };
  auto l = left_.next(config_.timeout_ms);
  if (!l) return fail(l.error(), left_);
  auto r = right_.next(config_.timeout_ms);
  if (!r) return fail(r.error(), right_);

  const std::int64_t max_skew_ns = config_.max_skew_us * 1000;
  const int budget = triggered ? 0 : config_.max_pair_frames;
  int reads_left = 1;
  int reads_right = 1;
  std::uint32_t skipped = 0;
  for (;;) {
    const PairStep step = pair_step(l->time_ns, r->time_ns, max_skew_ns);
    if (step == PairStep::pair) break;
    const bool again_left = step == PairStep::next_left;
    if ((again_left ? reads_left : reads_right) > budget) {
      ++health_.skew_failures;
      health_.last_fault = FrameFault::skew;
      return Error::make(Errc::timeout,
                         "stereo: no pair within %lld us (skew %lld us after %d left and %d "
                         "right frames)",
                         static_cast<long long>(config_.max_skew_us),
                         static_cast<long long>(abs_skew_ns(l->time_ns, r->time_ns) / 1000),
                         reads_left, reads_right);
    }
    ++skipped;
    if (again_left) {
      l = left_.next(config_.timeout_ms);
      if (!l) return fail(l.error(), left_);
      ++reads_left;
    } else {
      r = right_.next(config_.timeout_ms);
      if (!r) return fail(r.error(), right_);
      ++reads_right;
    }
  }
  PETRA_TRY(convert_to_gray(*l, left_.format(), 0, left));
  PETRA_TRY(convert_to_gray(*r, right_.format(), 0, right));
  StereoFrameInfo info;
  info.left_time_ns = l->time_ns;
  info.right_time_ns = r->time_ns;
  info.left_sequence = l->sequence;
  info.right_sequence = r->sequence;
  info.frames_skipped = skipped;
  return info;
}

}  // namespace petra::hal
