// The disparity range of an ROI, found coarse-to-fine: the onboard matcher
// (algo/stereo/match_dp) runs on a 1/factor box-downsampled copy of the rectified
// pair over the rig's whole working envelope (search_min_px..search_max_px at
// full resolution), and the range is the low..high quantiles of the coarse
// disparities (those pinned at the envelope's ends left out), scaled up,
// widened by a margin and clipped to the envelope.
// The operator gives only an ROI; a fixed envelope would cost the fine
// matcher 2-3 times more disparities than the rock needs.
// Inputs: rectified left/right (full size; the ROI and the right search area
// of the envelope must be filled), the ROI (rectified). Memory: from the arena,
// disparity_range_scratch_bytes, released on return. No heap.
#pragma once

#include <cstddef>

#include "algo/core/arena.hpp"
#include "algo/core/chain_defaults.hpp"
#include "algo/core/image_view.hpp"
#include "algo/core/result.hpp"
#include "algo/stereo/match_dp.hpp"

namespace petra {

struct RangeSearchParams {
  int search_min_px = kEnvelopeMinPx;  // working envelope, full-resolution px
  int search_max_px = kEnvelopeMaxPx;
  int factor = 4;  // coarse level (2 for ROIs under 128 px wide)
  double low_quantile = 0.02;
  double high_quantile = 0.98;
  int margin_px = 8;
  long min_matches = 30;  // coarse matches needed to trust the range
};

struct DisparityRange {
  int min_px = 0;
  int max_px = 0;
  int factor = 0;  // coarse level used
  long coarse_matches = 0;
};

Status validate(const RangeSearchParams& p);
int coarse_factor(const RangeSearchParams& p, int roi_width);
std::size_t disparity_range_scratch_bytes(int image_width, int image_height, int max_roi_width,
                                          int max_roi_height, const RangeSearchParams& p);

// `match` supplies the matcher settings (its disparity range is replaced).
Result<DisparityRange> find_disparity_range(ConstGray8View left, ConstGray8View right, Rect roi,
                                            const RangeSearchParams& params,
                                            const MatchDpParams& match, Arena& scratch);

}  // namespace petra
