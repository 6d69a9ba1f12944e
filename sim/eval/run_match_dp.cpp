#include "sim/eval/run_match_dp.hpp"

#include <algorithm>
#include <vector>

#include "sim/eval/disparity_image.hpp"

namespace petra::eval {

Result<MatchRun> run_match_dp(ConstGray8View left, ConstGray8View right, Rect roi,
                              const MatchDpParams& params) {
  const MatchBudget budget{std::max(roi.w, 1), std::max(roi.h, 1),
                           std::max(params.disp_max - params.disp_min + 1, 1)};
  std::vector<std::byte> scratch(match_dp_scratch_bytes(budget));
  Arena arena(scratch);
  std::vector<std::int16_t> q4(static_cast<std::size_t>(std::max(roi.w, 0)) * std::max(roi.h, 0));
  DisparityMap map{ImageView<std::int16_t>(q4.data(), std::max(roi.w, 0), std::max(roi.h, 0)), roi};
  StereoInput in;
  in.left = left;
  in.right = right;
  auto stats = match_dp(in, roi, params, budget, arena, map);
  if (!stats) return stats.error();
  MatchRun run;
  run.disparity = to_float_image(map, left.width(), left.height());
  run.stats = *stats;
  return run;
}

}  // namespace petra::eval
