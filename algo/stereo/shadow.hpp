// Shadow elimination (docs/method.md 1, paper 2.1). The cameras are monochrome and
// shadows are the darkest part of the ROI; ground experiments give the
// expected fraction p of shadow pixels. Per view, the threshold T is the gray
// value at which the ROI's cumulative histogram reaches p, and pixels <= T are
// shadow. Left and right thresholds are computed independently (the shadow's
// size differs between views). Shadow pixels get no disparity (algo/stereo/match_dp).
//
// Inputs: an 8-bit gray image, an ROI inside it, p in [0, 1).
// Outputs: the threshold (-1 = no shadow, when p = 0) and a mask over a
// caller-chosen area (255 = shadow, 0 = lit).
// Memory: a 256-bin histogram on the stack; the mask is caller memory of the
// area's size (w*h bytes). No heap.
#pragma once

#include <cstdint>

#include "algo/core/image_view.hpp"
#include "algo/core/result.hpp"

namespace petra {

inline constexpr std::uint8_t kShadowPixel = 255;

struct ShadowThreshold {
  int threshold = -1;      // gray level; pixels <= threshold are shadow (-1: none)
  long shadow_pixels = 0;  // pixels of the ROI at or below the threshold
  long roi_pixels = 0;
};

// Threshold where the ROI's cumulative histogram first reaches ceil(p * N)
// pixels. Errors: ROI empty or outside the image, p outside [0, 1), and an
// all-shadow ROI (every pixel at or below the threshold: nothing left to match).
Result<ShadowThreshold> shadow_threshold(ConstGray8View image, Rect roi, double fraction);

// Marks the pixels of `area` (image coordinates) at or below `threshold`;
// `mask` has the area's size. Returns the number of shadow pixels.
Result<long> shadow_mask(ConstGray8View image, Rect area, int threshold, Gray8View mask);

// The right view's windows for a left ROI matched over [disp_min, disp_max]
// in an image_width px wide pair: the mask covers the matcher's search area
// (right_search_area, empty when the range reaches no column), and the
// threshold's histogram an ROI-sized window at the middle disparity, clamped
// into the image (the shadow's share there is the ROI's). The one rule of
// the pipeline and of `petra stereo`.
struct RightShadowWindows {
  Rect histogram;
  Rect mask;
};
RightShadowWindows right_shadow_windows(Rect roi, int disp_min, int disp_max, int image_width);

// A mask over part of an image: pixels outside `area` are lit.
struct ShadowMask {
  ImageView<const std::uint8_t> mask;
  Rect area;

  bool is_shadow(int x, int y) const {
    return area.contains(x, y) && mask(x - area.x, y - area.y) != 0;
  }
};

}  // namespace petra
