// Sub-pixel refinement of an integer disparity map (the graph cut labels
// whole pixels; one pixel of disparity is several mm of depth at the rock,
// which makes the ground fit and the face normals coarse).
// For every valid pixel with disparity d: the sum of squared gray differences
// over a (2r+1)^2 window at d-2..d+2; the best of d-1, d, d+1 (a whole-pixel
// label may be one off), when a local minimum that is not flat, moves by the
// vertex of the parabola through it and its neighbours ([-0.5, 0.5] px),
// rounded to Q4. Pixels whose windows leave the image, or
// where d is not a minimum, keep their integer value.
// Inputs:  rectified left/right images of equal size (StereoInput; masks are
//          not used), the map over its ROI (rectified left pixels).
// Output:  the map, refined in place; the number of pixels refined.
// Memory:  none (no scratch, no heap). Time: 5 (2r+1)^2 per valid pixel.
#pragma once

#include "algo/core/result.hpp"
#include "algo/disparity.hpp"
#include "algo/match_dp.hpp"

namespace petra {

struct SubpixelParams {
  int window_radius = 2;  // px, 1..7
};
Status validate(const SubpixelParams& p);

Result<long> refine_subpixel(const StereoInput& in, const SubpixelParams& params,
                             DisparityMap& map);

}  // namespace petra
