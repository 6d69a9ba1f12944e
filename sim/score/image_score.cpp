#include "sim/score/image_score.hpp"

#include <cmath>
#include <limits>

namespace petra::sim {

namespace {

Status check_frame(int w, int h, int tw, int th, const Rect& region, const char* what) {
  if (w != tw || h != th)
    return Error::make(Errc::invalid_argument, "%s: output is %dx%d but the truth is %dx%d", what,
                       w, h, tw, th);
  if (!region.inside(tw, th))
    return Error::make(Errc::out_of_range, "%s: region %d,%d,%d,%d not inside the %dx%d image",
                       what, region.x, region.y, region.w, region.h, tw, th);
  return {};
}

double pct(long a, long b) {
  return b > 0 ? 100.0 * static_cast<double>(a) / static_cast<double>(b) : 0.0;
}

double ratio(long a, long b) {
  return b > 0 ? static_cast<double>(a) / static_cast<double>(b)
               : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace

Result<DisparityScore> score_disparity(const io::FloatImage& out, const io::FloatImage& truth,
                                       const Rect& region) {
  PETRA_TRY(check_frame(out.width, out.height, truth.width, truth.height, region, "disparity"));
  DisparityScore s;
  s.region = region;
  long bad1 = 0, bad2 = 0, bad1_valid = 0;
  double abs_sum = 0;
  const auto o = out.view();
  const auto t = truth.view();
  for (int y = region.y; y < region.y + region.h; ++y)
    for (int x = region.x; x < region.x + region.w; ++x) {
      const double td = t(x, y);
      if (!std::isfinite(td)) continue;
      ++s.truth_pixels;
      const double od = o(x, y);
      if (!std::isfinite(od)) {
        ++bad1;
        ++bad2;
        continue;
      }
      ++s.valid_pixels;
      const double e = std::abs(od - td);
      abs_sum += e;
      if (e > 1.0) {
        ++bad1;
        ++bad1_valid;
      }
      if (e > 2.0) ++bad2;
    }
  s.bad1_pct = pct(bad1, s.truth_pixels);
  s.bad2_pct = pct(bad2, s.truth_pixels);
  s.coverage_pct = pct(s.valid_pixels, s.truth_pixels);
  s.bad1_valid_pct = pct(bad1_valid, s.valid_pixels);
  s.mean_abs_error_px = s.valid_pixels > 0 ? abs_sum / static_cast<double>(s.valid_pixels) : 0.0;
  return s;
}

Result<MaskScore> score_mask(const io::GrayImage& out, const io::GrayImage& truth,
                             const Rect& region) {
  PETRA_TRY(check_frame(out.width, out.height, truth.width, truth.height, region, "shadow"));
  MaskScore s;
  s.region = region;
  const auto o = out.view();
  const auto t = truth.view();
  for (int y = region.y; y < region.y + region.h; ++y)
    for (int x = region.x; x < region.x + region.w; ++x) {
      const bool p = o(x, y) >= 128, q = t(x, y) >= 128;
      if (p && q) ++s.true_positive;
      if (p && !q) ++s.false_positive;
      if (!p && q) ++s.false_negative;
      if (!p && !q) ++s.true_negative;
    }
  s.precision = ratio(s.true_positive, s.true_positive + s.false_positive);
  s.recall = ratio(s.true_positive, s.true_positive + s.false_negative);
  s.iou = ratio(s.true_positive, s.true_positive + s.false_positive + s.false_negative);
  return s;
}

}  // namespace petra::sim
