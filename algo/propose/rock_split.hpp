// Rocks that touch or lie close are one connected region of the points
// standing out of the ground; this splits such a region where two height
// maxima meet at a saddle (issue 26; docs/proposals.md section 1). A
// persistence flood on the height above the ground: the rock points, highest
// first, each joining the part of its highest 8-neighbour already seen (a
// point with none starts a part: a local maximum); where a point touches two
// parts, the one with the lower peak joins the other unless its peak stands
// prominence_mm above this point (the saddle) and it holds min_pixels points
// (a lone mismatched spike or the relief of one face is not a rock).
// Output: per point its part's peak point, kNoSplitPart for points not rock.
// Scratch: two caller spans of one entry per point (detection lends its
// region ids and flood stack, unused until after the split). No heap.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "algo/core/result.hpp"
#include "algo/mesh/cloud.hpp"

namespace petra {

inline constexpr std::int32_t kNoSplitPart = -1;

struct SplitParams {
  double prominence_mm = 12.0;
  long min_pixels = 12;
};

// The points on a w x h grid: `index` per grid pixel (the point there, or
// < 0), `pixels` per point (its grid pixel).
struct SplitGrid {
  int w = 0, h = 0;
  std::span<const std::int32_t> index;
  std::span<const PixelPos> pixels;
};

// `height` per point (mm above the ground), `labels` per point; `part` per
// point, written; `order` and `sizes` per point, scratch.
Status split_at_saddles(const SplitGrid& grid, std::span<const float> height,
                        std::span<const PointClass> labels, const SplitParams& p,
                        std::span<std::int32_t> part, std::span<std::int32_t> order,
                        std::span<std::int32_t> sizes);

}  // namespace petra
