// Sub-pixel refinement of an integer disparity map (the graph cut labels
// whole pixels; one pixel of disparity is several mm of depth at the rock,
// which makes the ground fit and the face normals coarse).
// For every valid pixel with label d: the sum of squared gray differences
// over a (2r+1)^2 window at d-s-1 .. d+s+1 (s = search_px); the best of
// d-s .. d+s (the graph cut's Potts smoothness lays slanted faces out as
// whole-pixel stairs, off by up to a pixel or two), when a local minimum that
// is not flat, moves by the vertex of the parabola through it and its
// neighbours ([-0.5, 0.5] px), rounded to Q4. Pixels whose windows leave the
// image, or with no such minimum, keep their value.
// Inputs:  rectified left/right images of equal size (StereoInput; masks are
//          not used), the map over its ROI (rectified left pixels).
// Output:  the map, refined in place; the number of pixels refined.
// Memory:  none (no scratch, no heap). Time: (2s+3)(2r+1)^2 per valid pixel.
#pragma once

#include "algo/core/disparity.hpp"
#include "algo/core/result.hpp"
#include "algo/stereo/match_dp.hpp"

namespace petra {

inline constexpr int kMaxSearchPx = 4;

struct SubpixelParams {
  int window_radius = 2;  // px, 1..7
  int search_px = 2;      // px, 0..kMaxSearchPx: how far from its label a pixel may move
                          // (2: fewest face-normal errors of 1, 2, 3 on the set's small rocks)
};
Status validate(const SubpixelParams& p);

Result<long> refine_subpixel(const StereoInput& in, const SubpixelParams& params,
                             DisparityMap& map);

}  // namespace petra
