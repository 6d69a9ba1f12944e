// Edge-constrained scanline dynamic-programming stereo matcher (docs/method.md 2b,
// the paper's fast path). On rectified images, for the ROI of the left view:
//   1. Canny edges in the left ROI and the right search area (algo/stereo/canny).
//   2. Per scanline, left and right edge points sorted by u are paired by
//      gray-level correlation (ZNCC) under the ordering constraint, by DP
//      (algo/stereo/edge_pairs). Pairs are kept as anchors only if the dense cost
//      agrees: the left and the right winner of the aggregated cost lie within
//      edge_tolerance_px of the pair, with a uniqueness margin.
//   3. Non-edge pixels between two anchors are matched within the bounds the
//      anchors give (ordering: the right match lies between the anchors' right
//      points, +- edge_tolerance_px), by a scanline DP (algo/stereo/scanline_dp) over
//      a census + intensity cost aggregated on a 5x9 shiftable window
//      (algo/stereo/match_cost). The DP has a small penalty P1 for one-pixel steps and
//      a larger one P2 for jumps, lowered at intensity edges. Beside the
//      upright 5x9 box, a slanted one (rows sheared by half a pixel of
//      disparity per row, for faces turned up to the sky) where it is cheaper.
//   4. Wrong matches are removed: left-right consistency (the right view's
//      winner along the same path costs), uniqueness, a ceiling on the mean
//      matching cost (the dense counterpart of a correlation floor), the right
//      match outside the image or in the right shadow, and left shadow pixels.
//   5. Sub-pixel refinement by a parabola through the path costs at the best
//      disparity and its neighbours; a 3x3 median over valid neighbours
//      removes isolated spikes.
// Beyond the paper: the dense step's cost (census + intensity, aggregated) and
// the two-direction DP with P1/P2; the paper gives no detail for it.
//
// Output: DisparityMap (algo/core/disparity.hpp) of the ROI, Q4 = 1/16 px, left
// view, invalid = kInvalidDisparity; optional confidence 0..255 (0 = invalid;
// otherwise the relative margin of the best path cost over the best cost at
// any disparity more than 1 px away).
//
// Memory: all from the caller's Arena, released on return, no heap.
// match_dp_scratch_bytes(budget) bounds it for any ROI and range within the
// budget. With w x h the ROI, D the disparity count, Dp = D rounded up to 16
// (to 32 where the AVX-512 copy runs: lane_multiple(), algo/stereo/vector_clones.hpp),
// B = w + D - 1 the right search width and wc = w + 8, the arena holds (the
// budget takes Dp at 32 lanes on every CPU: one flight memory table everywhere)
//   edge maps (whole call)       w h + B h
//   then Canny (transient)       about 11 B h           (one view at a time)
//   or the row buffers:
//     raw cost window (9 rows)   9 wc Dp
//     column sums, box sums      2 wc Dp + 10 Dp            (box sums: a ring of 5)
//     slanted box: sums, cost    2 wc Dp + 2 w Dp + w
//     two rows in flight: cost, path costs S and backward, bounds, penalties
//                                2 (2 w Dp + 4 w (Dp + 16) + 6 w)   (S: D rounded
//                                up to 16 lanes, at most Dp)
//     right-view winners         64 (w + Dp) + 4 (w + Dp)   (16 chains, keys)
//     edge DP table (per row)    (w + 1)(B + 1) + 58 (w + B) + 12 B
//     row vectors                about 14 (wc + Dp) + 50 w  (checks: 20 w)
//     each buffer starts on a 64-byte line (64 bytes of slack each)
// Flight budget (320 x 320 px, 128 disparities): 1 841 243 bytes (1.76 MiB),
// the peak being Canny of the right search area (the row buffers: 1.41 MB);
// 160 x 160 px with 42 disparities: 448 451 bytes. docs/matching.md has the
// table. Lane kernels also have x86-64-v3 and -v4 copies chosen at load
// (algo/stereo/vector_clones.hpp); outputs are the same bit for bit.
#pragma once

#include <cstddef>
#include <cstdint>

#include "algo/core/arena.hpp"
#include "algo/core/disparity.hpp"
#include "algo/core/image_view.hpp"
#include "algo/core/result.hpp"
#include "algo/stereo/canny.hpp"
#include "algo/stereo/match_photometric.hpp"
#include "algo/stereo/shadow.hpp"

namespace petra {

// The largest problem the caller has memory for (fixed at init).
struct MatchBudget {
  int max_width = 320;
  int max_height = 320;
  int max_disparities = 128;  // disp_max - disp_min + 1
};

struct MatchDpParams {
  int disp_min = 0;  // px, right = left - d
  int disp_max = 63;
  CannyParams canny{};
  bool edge_constraint = true;   // steps 2-3; off only to measure their effect
  int edge_zncc_floor_pct = 80;  // correlation floor of an edge pair
  int edge_uniqueness_pct = 10;  // anchor: margin of the dense winner
  int edge_tolerance_px = 1;     // edge localisation slack of the bounds
  // The slanted box beside the upright one (algo/stereo/match_cost): consulted
  // at a pixel whose upright best mean raw cost (0..24) exceeds
  // slant_min_mean_cost, and charged slant_penalty (aggregated units,
  // 0..1000) where it wins.
  bool slanted_window = true;
  int slant_min_mean_cost = 4;
  int slant_penalty = 60;
  int p1 = 100;  // DP penalty of a one-pixel step (cost units)
  int p2 = 900;  // DP penalty of a jump, before edge lowering
  int lr_tolerance_px = 1;
  int uniqueness_pct = 5;
  int max_mean_cost = 10;  // ceiling of the mean raw cost (0..24) in the window
  bool median = true;
  // The right view's gray levels mapped to the left's before the intensity
  // term (algo/stereo/match_photometric), the map measured on the edge pairs'
  // windows (on the areas' statistics without the edge constraint); the
  // identity where the two cameras agree within what it resolves.
  bool normalise_gray = true;
};

struct MatchDpStats {
  long roi_pixels = 0;
  long matched = 0;  // valid disparities written
  long shadow_left = 0;
  long rejected_lr = 0;
  long rejected_uniqueness = 0;
  long rejected_cost = 0;
  long rejected_range = 0;  // right match outside the image
  long rejected_shadow_right = 0;
  long left_edges = 0;
  long right_edges = 0;
  long edge_pairs = 0;                 // from the edge DP
  long anchors = 0;                    // pairs kept as constraints
  int gray_gain_q8 = 256;              // the gray-level map applied (step 0), 1/256
  int gray_offset_q8 = 0;              // its level(0), 1/256 gray level
  std::size_t scratch_high_water = 0;  // arena bytes used at the peak
};

// The rectified pair and optional shadow masks (algo/stereo/shadow) of each view.
struct StereoInput {
  ConstGray8View left;
  ConstGray8View right;
  const ShadowMask* left_shadow = nullptr;
  const ShadowMask* right_shadow = nullptr;
};

// Bytes of Arena match_dp needs at most for any call within `budget`.
std::size_t match_dp_scratch_bytes(const MatchBudget& budget);

// Columns of the right view that the ROI's disparity range can reach (rows
// of the ROI), clipped to the image; empty when none. Shadow masks of the
// right view should cover it.
Rect right_search_area(Rect roi, int disp_min, int disp_max, int image_width);

// Step 0 alone: the gray-level map match_dp would apply to the right view
// (the identity with normalise_gray off, no right search area or a
// textureless ROI); the graph cut reads its right view through it. Scratch
// from `arena` (at most match_dp_scratch_bytes(budget)), released on return.
Result<match::GrayMap> match_dp_gray_map(const StereoInput& in, Rect roi,
                                         const MatchDpParams& params, const MatchBudget& budget,
                                         Arena& arena);

// Matches `roi` of the left view. `out.q4` must have the ROI's size; out.roi
// is set to `roi`. `confidence` is empty or ROI-sized.
// Errors: images of different sizes; empty or outside ROI; ROI or disparity
// range larger than the budget; empty range; bad parameters; no right search
// area; an all-shadow ROI; a textureless ROI (too few edge pixels); arena too
// small (names the buffer).
Result<MatchDpStats> match_dp(const StereoInput& in, Rect roi, const MatchDpParams& params,
                              const MatchBudget& budget, Arena& scratch, DisparityMap& out,
                              ImageView<std::uint8_t> confidence = {});

}  // namespace petra
