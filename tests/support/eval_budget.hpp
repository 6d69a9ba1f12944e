// The pipeline budget the real-data tests give the chain, as `petra eval` sizes
// it: the pair's size, an ROI bound, one 3-D point per ROI pixel and the
// default envelope's disparities.
#pragma once

#include <cstddef>

#include "algo/chain/pipeline.hpp"

namespace petra::test {

inline PipelineBudget eval_budget(int image_width, int image_height, int max_roi,
                                  const PipelineParams& params) {
  PipelineBudget b;
  b.image_width = image_width;
  b.image_height = image_height;
  b.max_roi_width = max_roi;
  b.max_roi_height = max_roi;
  b.max_points = static_cast<std::size_t>(max_roi) * static_cast<std::size_t>(max_roi);
  b.max_disparities = params.range.search_max_px - params.range.search_min_px + 1;
  return b;
}

}  // namespace petra::test
