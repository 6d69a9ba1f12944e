#include "hal/stereo_assembler.hpp"

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

Status check_stereo_timing(const StereoTiming& t) {
  if (t.width <= 0 || t.height <= 0)
    return Error::make(Errc::invalid_argument, "stereo: view size %dx%d must be positive", t.width,
                       t.height);
  if (t.timeout_ms <= 0 || t.timeout_ms > 60'000)
    return Error::make(Errc::invalid_argument, "stereo: timeout_ms %d outside 1..60000",
                       t.timeout_ms);
  if (t.max_skew_us < 0 || t.max_skew_us > 1'000'000)
    return Error::make(Errc::invalid_argument, "stereo: max_skew_us %lld outside 0..1000000",
                       static_cast<long long>(t.max_skew_us));
  if (t.max_pair_frames < 1 || t.max_pair_frames > 64)
    return Error::make(Errc::invalid_argument, "stereo: max_pair_frames %d outside 1..64",
                       t.max_pair_frames);
  if (t.trigger != nullptr && (t.trigger_width_us == 0 || t.trigger_width_us > 1'000'000))
    return Error::make(Errc::invalid_argument, "stereo: trigger_width_us %u outside 1..1000000",
                       t.trigger_width_us);
  return ok_status();
}

namespace {

Error fail(const Error& e, const FrameSource& side, StereoHealth& health) {
  health.last_fault = side.health().last_fault;
  return e;
}

Result<StereoFrameInfo> one_camera(const StereoTiming& t, FrameSource& cam, Gray8View l,
                                   Gray8View r, StereoHealth& health) {
  auto frame = cam.next(t.timeout_ms);
  if (!frame) return fail(frame.error(), cam, health);
  if (t.layout == StereoLayout::side_by_side) {
    if (cam.format().width != 2 * t.width)
      return Error::make(Errc::invalid_argument, "stereo: side-by-side frame %d wide, need %d",
                         cam.format().width, 2 * t.width);
    PETRA_TRY(convert_to_gray(*frame, cam.format(), 0, l));
    PETRA_TRY(convert_to_gray(*frame, cam.format(), t.width, r));
  } else {
    PETRA_TRY(deinterleave_pair(*frame, cam.format(), l, r));
  }
  StereoFrameInfo info;
  info.left_time_ns = info.right_time_ns = frame->time_ns;
  info.left_sequence = info.right_sequence = frame->sequence;
  return info;
}

Result<StereoFrameInfo> two_cameras(const StereoTiming& t, FrameSource& left, FrameSource& right,
                                    Gray8View lv, Gray8View rv, StereoHealth& health) {
  auto l = left.next(t.timeout_ms);
  if (!l) return fail(l.error(), left, health);
  auto r = right.next(t.timeout_ms);
  if (!r) return fail(r.error(), right, health);

  const std::int64_t max_skew_ns = t.max_skew_us * 1000;
  const int budget = t.trigger != nullptr ? 1 : t.max_pair_frames;
  int reads_left = 1;
  int reads_right = 1;
  std::uint32_t skipped = 0;
  for (;;) {
    const PairStep step = pair_step(l->time_ns, r->time_ns, max_skew_ns);
    if (step == PairStep::pair) break;
    const bool again_left = step == PairStep::next_left;
    if ((again_left ? reads_left : reads_right) >= budget) {
      ++health.skew_failures;
      health.last_fault = FrameFault::skew;
      return Error::make(Errc::timeout,
                         "stereo: no pair within %lld us (skew %lld us after %d left and %d "
                         "right frames)",
                         static_cast<long long>(t.max_skew_us),
                         static_cast<long long>(abs_skew_ns(l->time_ns, r->time_ns) / 1000),
                         reads_left, reads_right);
    }
    ++skipped;
    if (again_left) {
      l = left.next(t.timeout_ms);
      if (!l) return fail(l.error(), left, health);
      ++reads_left;
    } else {
      r = right.next(t.timeout_ms);
      if (!r) return fail(r.error(), right, health);
      ++reads_right;
    }
  }
  PETRA_TRY(convert_to_gray(*l, left.format(), 0, lv));
  PETRA_TRY(convert_to_gray(*r, right.format(), 0, rv));
  StereoFrameInfo info;
  info.left_time_ns = l->time_ns;
  info.right_time_ns = r->time_ns;
  info.left_sequence = l->sequence;
  info.right_sequence = r->sequence;
  info.frames_skipped = skipped;
  return info;
}

}  // namespace

Result<StereoFrameInfo> assemble_pair(const StereoTiming& t, FrameSource& left, FrameSource* right,
                                      Gray8View left_view, Gray8View right_view,
                                      StereoHealth& health) {
  if (left_view.width() != t.width || left_view.height() != t.height ||
      right_view.width() != t.width || right_view.height() != t.height)
    return Error::make(Errc::invalid_argument, "stereo: views %dx%d and %dx%d, camera gives %dx%d",
                       left_view.width(), left_view.height(), right_view.width(),
                       right_view.height(), t.width, t.height);
  const bool two = t.layout == StereoLayout::two_devices;
  if (two && right == nullptr)
    return Error::make(Errc::invalid_argument, "stereo: two_devices layout without a right camera");
  if (t.trigger != nullptr) {
    PETRA_TRY(pulse(*t.trigger, t.trigger_width_us));
  } else {
    PETRA_TRY(left.flush());
    if (two) PETRA_TRY(right->flush());
  }
  auto r = two ? two_cameras(t, left, *right, left_view, right_view, health)
               : one_camera(t, left, left_view, right_view, health);
  if (r) ++health.pairs;
  return r;
}

}  // namespace petra::hal
