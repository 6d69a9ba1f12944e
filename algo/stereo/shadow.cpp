#include "algo/stereo/shadow.hpp"

#include <algorithm>
#include <cmath>

#include "algo/stereo/match_dp.hpp"

namespace petra {

namespace {

Status check_area(ConstGray8View image, Rect r, const char* what) {
  if (r.empty())
    return Error::make(Errc::invalid_argument, "shadow: %s %dx%d is empty", what, r.w, r.h);
  if (!r.inside(image.width(), image.height()))
    return Error::make(Errc::out_of_range, "shadow: %s (%d,%d %dx%d) is outside the %dx%d image",
                       what, r.x, r.y, r.w, r.h, image.width(), image.height());
  return ok_status();
}

}  // namespace

Result<ShadowThreshold> shadow_threshold(ConstGray8View image, Rect roi, double fraction) {
  PETRA_TRY(check_area(image, roi, "ROI"));
  if (!(fraction >= 0.0 && fraction < 1.0))
    return Error::make(Errc::invalid_argument, "shadow: fraction %g outside [0, 1)", fraction);
  ShadowThreshold out;
  out.roi_pixels = roi.area();
  if (fraction == 0.0) return out;

  std::uint32_t histogram[256] = {};
  for (int y = roi.y; y < roi.y + roi.h; ++y) {
    const std::uint8_t* row = image.row(y);
    for (int x = roi.x; x < roi.x + roi.w; ++x) ++histogram[row[x]];
  }
  const long target = static_cast<long>(std::ceil(fraction * static_cast<double>(out.roi_pixels)));
  long cumulative = 0;
  for (int g = 0; g < 256; ++g) {
    cumulative += histogram[g];
    if (cumulative >= target) {
      out.threshold = g;
      out.shadow_pixels = cumulative;
      break;
    }
  }
  // Many pixels sharing the threshold value can carry the count to the whole
  // ROI (a uniformly dark ROI): then there is nothing left to match.
  if (out.shadow_pixels >= out.roi_pixels)
    return Error::make(Errc::degenerate,
                       "shadow: all %ld pixels of the ROI are at or below the threshold %d "
                       "(all shadow)",
                       out.roi_pixels, out.threshold);
  return out;
}

Result<long> shadow_mask(ConstGray8View image, Rect area, int threshold, Gray8View mask) {
  PETRA_TRY(check_area(image, area, "mask area"));
  if (mask.width() != area.w || mask.height() != area.h)
    return Error::make(Errc::invalid_argument, "shadow: mask is %dx%d, area is %dx%d", mask.width(),
                       mask.height(), area.w, area.h);
  if (threshold < -1 || threshold > 255)
    return Error::make(Errc::invalid_argument, "shadow: threshold %d outside [-1, 255]", threshold);
  long count = 0;
  for (int y = 0; y < area.h; ++y) {
    const std::uint8_t* src = image.row(area.y + y) + area.x;
    std::uint8_t* dst = mask.row(y);
    for (int x = 0; x < area.w; ++x) {
      const bool shadow = src[x] <= threshold;
      dst[x] = shadow ? kShadowPixel : 0;
      count += shadow;
    }
  }
  return count;
}

RightShadowWindows right_shadow_windows(Rect roi, int disp_min, int disp_max, int image_width) {
  Rect histogram = roi;
  histogram.x = std::clamp(roi.x - (disp_min + disp_max) / 2, 0, image_width - roi.w);
  return {histogram, right_search_area(roi, disp_min, disp_max, image_width)};
}

}  // namespace petra
