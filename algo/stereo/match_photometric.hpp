// Photometric normalisation of the right view before matching: two cameras
// differ in gain and offset (exposure, amplifier, lens transmission), and an
// intensity cost compares gray values across them. The right view's gray
// levels are mapped linearly, level(v) = gain v + offset, with the map
// measured one of two ways:
// - on correspondences (the matchers' default, algo/stereo/match_dp step 0):
//   the windows of the DP's edge pairs, medians of the pairs' own gains and
//   offsets (PairGainVotes, PairOffsetVotes below);
// - on areas (the DP without its edge constraint): the mean and the mean
//   absolute deviation of the right search area made equal to the left
//   ROI's, from 256-bin histograms of 4x2 block means (robust to a
//   sub-pixel resampling of one view), the left ROI against the right area it
//   lands on at the middle of the disparity range. Those areas see other
//   content wherever the disparity varies, which the pairs do not.
// Integer arithmetic only. Census (algo/stereo/match_cost) compares pixels
// within one view, so it is unchanged by any increasing map; the map matters
// to the intensity terms.
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

// The map from corresponding windows: the 5x5 windows of the edge pairs
// (matched by ZNCC, which a gain and offset do not change) see the same
// scene points in both views. Pass 1 takes the median of the pairs' own
// gains (ratio of the windows' deviations); pass 2 the median of their
// offsets (mean_L - gain mean_R) over the pairs whose gain agrees with it.
// Medians, not moments: pairs across a depth edge or wrongly matched see
// other content.
inline constexpr int kPairWindowRadius = 2;
inline constexpr int kPairWindowArea = (2 * kPairWindowRadius + 1) * (2 * kPairWindowRadius + 1);
inline constexpr int kMinWindowDev = 16 * 16 * 4 * 4;  // 2x2 blocks' mean |dev| >= 4 levels
inline constexpr int kMinGainQ8 = 256 / kMaxGrayGain, kMaxGainQ8 = 256 * kMaxGrayGain;
inline constexpr int kGainBins = kMaxGainQ8 - kMinGainQ8 + 1;
inline constexpr int kMaxOffset2 = 510;  // offsets within +-255 levels, in half levels
inline constexpr int kOffsetBins = 2 * kMaxOffset2 + 1;
inline constexpr int kMinMapPairs = 50;    // fewer: the identity
inline constexpr int kIdentityGainQ8 = 5;  // |gain - 1| <= 2 %
inline constexpr int kIdentityLevels = 2;  // and mid-gray moved by <= 2 levels
struct PairGainVotes {
  std::int32_t votes[kGainBins] = {};
  int pairs = 0;
  void add(ConstGray8View left, int xl, ConstGray8View right, int xr, int y);
  int median_gain_q8() const;
};
struct PairOffsetVotes {
  int gain_q8 = 256;  // the median of pass 1
  std::int32_t votes[kOffsetBins] = {};
  int pairs = 0;
  void add(ConstGray8View left, int xl, ConstGray8View right, int xr, int y);
};
GrayMap gray_map_from_pairs(const PairOffsetVotes& s);

// The map level(v) = (gain_q8 v + offset_q8) / 256, rounded and clamped.
GrayMap linear_gray_map(std::int64_t gain_q8, std::int64_t offset_q8);

// dst[i] = map(src[i]) for n bytes (dst may be src).
void apply_gray_map(const GrayMap& map, const std::uint8_t* src, int n, std::uint8_t* dst);

}  // namespace petra::match
