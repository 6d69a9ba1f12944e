// Photometric normalisation of the right view before matching: two cameras
// differ in gain and offset (exposure, amplifier, lens transmission), and an
// intensity cost compares gray values across them. The right view's gray
// levels are mapped linearly so that the mean and the mean absolute
// deviation of the right search area equal those of the left ROI:
//   level(v) = mean_L + (v - mean_R) * mad_L / mad_R   (rounded, clamped 0..255)
// Both statistics come from 256-bin histograms of 4x2 block means (robust to
// a sub-pixel resampling of one view), integer arithmetic only.
// The two areas see the same scene: the left ROI and the right area it
// lands on at the middle of the disparity range (both cut to the columns
// where that shift stays inside the image). Statistics of a wider right
// area (the whole search band) describe other content and gave a wrong map
// on small ROIs. Census (algo/stereo/match_cost) compares pixels within one view,
// so it is unchanged by any increasing map; the map matters to the
// intensity terms.
#pragma once

#include <cstdint>

#include "algo/core/image_view.hpp"

namespace petra::match {

// The gain mad_L / mad_R is kept within [1/4, 4]; outside, the statistics
// describe different content, not a camera difference.
inline constexpr int kMaxGrayGain = 4;

struct GrayMap {
  std::uint8_t level[256];
  int gain_q8 = 256;  // mad_L / mad_R in 1/256
  int offset_q8 = 0;  // level(0) before rounding and clamping, 1/256 gray level
  std::uint8_t operator()(std::uint8_t v) const { return level[v]; }
};

// The identity map (no normalisation).
GrayMap identity_gray_map();

// The map for matching `roi` of the left view over disparities
// [disp_min, disp_max] (right x = left x - d): the areas described above.
GrayMap gray_map_for_roi(ConstGray8View left, ConstGray8View right, Rect roi, int disp_min,
                         int disp_max);

// The map taking the right view's `right_area` to the statistics of the left
// view's `left_area`. Both areas are clipped to their images; an empty or
// flat area (no deviation) gives a pure offset or the identity.
GrayMap right_to_left_gray_map(ConstGray8View left, Rect left_area, ConstGray8View right,
                               Rect right_area);

// dst[i] = map(src[i]) for n bytes (dst may be src).
void apply_gray_map(const GrayMap& map, const std::uint8_t* src, int n, std::uint8_t* dst);

}  // namespace petra::match
