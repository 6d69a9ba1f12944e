#include "sim/eval/propose_budget.hpp"

#include <algorithm>
#include <utility>

#include "algo/camera/rectify.hpp"

namespace petra::eval {

Result<ProposerBudget> ground_proposer_budget(const StereoRig& rig, const PipelineParams& params) {
  auto pair = rectify_geometry(rig, rig.left.width, rig.left.height);
  if (!pair) return pair.error();
  const int W = rig.left.width, H = rig.left.height;
  const int w = std::min(kProposalRoiWidth, W), h = std::min(kProposalRoiHeight, H);
  ProposerBudget b;
  b.max_roi_width = w;
  b.max_roi_height = h;
  PipelineBudget& p = b.pipeline;
  p.image_width = W;
  p.image_height = H;
  int bw = w, bh = h;
  for (const auto& [x, y] :
       {std::pair{0, 0}, {W - w, 0}, {0, H - h}, {W - w, H - h}, {(W - w) / 2, (H - h) / 2}}) {
    auto r = roi_to_rectified(rig.left, pair->left, Rect{x, y, w, h}, W, H);
    if (r) bw = std::max(bw, r->w), bh = std::max(bh, r->h);
  }
  p.max_roi_width = std::min(bw + 1, W);
  p.max_roi_height = std::min(bh + 1, H);
  p.max_points =
      static_cast<std::size_t>(p.max_roi_width) * static_cast<std::size_t>(p.max_roi_height);
  p.max_disparities = params.range.search_max_px - params.range.search_min_px + 1;
  return b;
}

}  // namespace petra::eval
