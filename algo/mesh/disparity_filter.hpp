// Disparity mean filter (docs/method.md 3c, paper Table 1: 23465 -> 21382 points):
// removes spikes before triangulation. For every valid pixel, the mean of the
// VALID NEIGHBOURS in a window x window box (the pixel itself excluded, box
// clipped at the map border) is compared with its disparity; the pixel is
// invalidated when they differ by more than the tolerance, or when fewer than
// min_support neighbours are valid (an isolated match cannot be checked; a
// pixel with no valid neighbour at all is always removed).
// Invalidate rather than replace: a replaced value would be a measurement
// nobody made, and the Delaunay mesh bridges the hole anyway.
// Integer arithmetic on Q4 disparities (exact comparison |n*d - sum| > n*tol).
// Inputs: a DisparityMap (algo/core/disparity.hpp); output: a map of the same size
// (distinct memory). Scratch: mean_filter_scratch_bytes(width) from the arena,
// released on return. No heap.
#pragma once

#include <cstddef>

#include "algo/core/arena.hpp"
#include "algo/core/disparity.hpp"
#include "algo/core/result.hpp"

namespace petra {

struct MeanFilterParams {
  int window = 5;             // odd, 3..31 px
  double tolerance_px = 1.0;  // largest |d - neighbour mean| kept, px (> 0)
  int min_support = 3;        // fewest valid neighbours a kept pixel needs (>= 0)
};

struct MeanFilterStats {
  long before = 0;            // valid pixels in the input ("dense points")
  long after = 0;             // valid pixels in the output ("filtered points")
  long removed_spikes = 0;    // farther than the tolerance from their neighbour mean
  long removed_isolated = 0;  // fewer than min_support valid neighbours
};

Status validate(const MeanFilterParams& p);

std::size_t mean_filter_scratch_bytes(int width);

// `out` may not alias `in`; both must have the same size.
Result<MeanFilterStats> mean_filter_disparity(ConstDisparityMap in, DisparityMap out,
                                              const MeanFilterParams& params, Arena& scratch);

// Counts valid pixels of a map.
long count_valid(ConstDisparityMap map);

}  // namespace petra
