// Dynamic programming along one scanline for algo/stereo/match_dp: the path cost
//   L(x, k) = C(x, k) + min(L(x-1, k), L(x-1, k+-1) + P1, min_j L(x-1, j) + P2(x)) - min_j L(x-1,
//   j)
// is run left-to-right and right-to-left and summed, S = L_fwd + L_bwd, so
// that argmin_k S(x, .) is the disparity of the best path through x (the
// min-marginal of the scanline's chain). Changing the disparity by one pixel
// costs P1 (slanted surfaces); a larger jump costs P2(x), lowered where the
// image has an intensity edge, since depth edges coincide with image edges.
// Cells outside [lo(x), hi(x)] (the bounds the matched edge pairs give) get
// kForbiddenCost added (apply_bounds), so no best path uses them: an allowed
// cell's S stays below 2 (kAggregatedMax + kMaxP2) < kForbiddenCost.
// Integer int16 arithmetic; values stay below 2 * (kAggregatedMax +
// 2 kForbiddenCost + kMaxP2) < 32767.
#pragma once

#include <cstdint>

namespace petra::match {

inline constexpr int kForbiddenCost = 4096;
inline constexpr int kMaxP2 = 960;

// cost[x][k] += kForbiddenCost for k outside [lo[x], hi[x]]; columns with
// lo <= 0 and hi >= full_hi (no constraint) are skipped.
template <int kLanes>  // see PETRA_MATCH_LANE_COUNTS (algo/stereo/match_cost.hpp)
void apply_bounds(std::uint16_t* cost, int n, int stride, const std::int16_t* lo,
                  const std::int16_t* hi, int full_hi);

// S rows have kGuardLanes guard lanes before and after the stride lanes.
inline constexpr int kGuardLanes = 8;
constexpr int path_row_stride(int stride) {
  return stride + 2 * kGuardLanes;
}

struct ScanlineInputs {
  const std::uint16_t* cost;  // n x stride, aggregated matching cost, bounds applied
  int n;                      // columns
  int stride;                 // disparity lanes per column (multiple of 8)
  const std::uint16_t* p2;    // per column x >= 1: penalty for a jump between x-1 and x
  int p1;
  // Lanes the DP runs over and of the path rows, 0 < lanes <= stride (0:
  // stride). The cost lanes from `lanes` to `stride` are padding that never
  // wins (a cost row rounded up to a 512-bit multiple): the DP skips them.
  int lanes = 0;
  // false: S is left holding the forward path costs alone, for a caller that
  // adds `backward` itself as it first reads S (one pass over S fewer).
  bool sum_paths = true;
};

// S = forward + backward path costs: n rows of path_row_stride(lanes)
// int16, lanes of column x at S + x * path_row_stride + kGuardLanes (the
// forward pass writes there directly; the guards are set here). `backward`
// is scratch of the same size (n rows of path_row_stride(lanes) int16): the
// backward pass keeps every row so the two passes run interleaved.
// kLanes: the lanes the DP runs over (ScanlineInputs::lanes), or 0 for any.
template <int kLanes>
void scanline_dp(const ScanlineInputs& in, std::int16_t* S, std::int16_t* backward);

// Two independent scanlines at once (same n and stride), each as
// scanline_dp: the same results, faster where the DP is latency-bound.
template <int kLanes>
void scanline_dp_pair(const ScanlineInputs& a, std::int16_t* Sa, std::int16_t* backward_a,
                      const ScanlineInputs& b, std::int16_t* Sb, std::int16_t* backward_b);

}  // namespace petra::match
