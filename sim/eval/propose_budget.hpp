// The proposer's budget on the ground (`petra propose`, its tests): chain
// defaults as `petra eval` (one 3-D point per ROI pixel, the default
// envelope's disparities), candidate ROIs up to SELECT_ROI's flight default
// 512 x 384 original px, the chain sized for the rectified box any such ROI
// maps to (largest over the image's corners and centre, plus a pixel).
#pragma once

#include "algo/propose/proposer.hpp"

namespace petra::eval {

inline constexpr int kProposalRoiWidth = 512;
inline constexpr int kProposalRoiHeight = 384;

Result<ProposerBudget> ground_proposer_budget(const StereoRig& rig, const PipelineParams& params);

}  // namespace petra::eval
