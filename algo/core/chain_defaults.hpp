// Defaults of the onboard chain that the flight service's parameter table
// (cmd/param_defs.hpp: SHADOW_FRACTION, DISP_MIN_PX, DISP_MAX_PX) and the
// library's parameter structs (PipelineParams, RangeSearchParams) share, so
// the service and `petra eval` run the same chain on the same pair.
#pragma once

namespace petra {

// Disparity working envelope of the rig, full-resolution px.
inline constexpr int kEnvelopeMinPx = 64;
inline constexpr int kEnvelopeMaxPx = 320;

// Expected shadow share of the ROI. Only the darkest 1 %: self-shadowed rock
// faces are grind candidates and still match. Measured on the realistic set
// (docs/matching.md "Shadow prior"): 0.1 gives the best shadow mask (IoU
// 0.44 against 0.09) but worse planes (centroids on their facet 44 of 59
// against 56), so the planes decide.
inline constexpr double kShadowFraction = 0.01;

}  // namespace petra
