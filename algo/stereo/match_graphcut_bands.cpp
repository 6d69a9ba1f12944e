#include "algo/stereo/match_graphcut_bands.hpp"

#include <algorithm>
#include <cstring>

namespace petra {

namespace {

constexpr std::size_t kSlack = 256;

bool split(int height, GraphCutBands b) {
  return b.rows > 0 && height > b.rows + 2 * b.overlap;
}

}  // namespace

int graph_cut_band_height(int max_height, GraphCutBands bands) {
  return split(max_height, bands) ? bands.rows + 2 * bands.overlap : max_height;
}

std::size_t graph_cut_bands_bytes(const GraphCutBudget& budget, GraphCutBands bands) {
  const int h = graph_cut_band_height(budget.max_height, bands);
  const std::size_t band_map = split(budget.max_height, bands)
                                   ? static_cast<std::size_t>(budget.max_width) *
                                         static_cast<std::size_t>(h) * sizeof(std::int16_t)
                                   : 0;
  return GraphCutMatcher::bytes_needed({budget.max_width, h, budget.max_disparities}) + band_map +
         kSlack;
}

Result<GraphCutReport> match_graph_cut_bands(const StereoInput& in, Rect roi,
                                             const GraphCutParams& params, GraphCutBands bands,
                                             Arena& arena, DisparityMap& out) {
  if (bands.rows < 0 || bands.overlap < 0)
    return Error::make(Errc::invalid_argument, "graphcut bands: rows %d, overlap %d", bands.rows,
                       bands.overlap);
  const int count = params.disp_max - params.disp_min + 1;
  const ArenaScope scope(arena);
  GraphCutMatcher matcher;
  if (!split(roi.h, bands)) {
    PETRA_TRY(matcher.init(arena, GraphCutBudget{roi.w, roi.h, count}));
    return matcher.match(in, roi, params, out);
  }
  if (params.start == GraphCutStart::given)
    return Error::make(Errc::invalid_argument, "graphcut bands: a given start map needs one band");
  if (out.q4.width() != roi.w || out.q4.height() != roi.h)
    return Error::make(Errc::invalid_argument, "graphcut bands: output %dx%d for a %dx%d ROI",
                       out.q4.width(), out.q4.height(), roi.w, roi.h);
  const int band_h = bands.rows + 2 * bands.overlap;
  PETRA_TRY(matcher.init(arena, GraphCutBudget{roi.w, band_h, count}));
  auto buf = arena.allocate_uninitialised<std::int16_t>(
      static_cast<std::size_t>(roi.w) * static_cast<std::size_t>(band_h), "graphcut band map");
  if (!buf) return buf.error();
  // One automatic K for the whole ROI (the row-weighted mean of the bands'),
  // so every band weighs occlusion and smoothness alike.
  GraphCutParams p = params;
  if (p.occlusion_k == kGraphCutAuto) {
    double sum = 0;
    int rows = 0;
    for (int y0 = 0; y0 < roi.h; y0 += bands.rows) {
      const int h = std::min(roi.h - y0, bands.rows);
      auto k = matcher.automatic_occlusion_k(in, Rect{roi.x, roi.y + y0, roi.w, h}, params);
      if (!k) continue;  // no pixel with enough disparities: it does not vote
      sum += static_cast<double>(*k) * h;
      rows += h;
    }
    if (rows > 0) p.occlusion_k = static_cast<std::int32_t>(sum / rows + 0.5);
  }
  GraphCutReport total;
  for (int y0 = 0; y0 < roi.h; y0 += bands.rows) {
    const int y1 = std::min(roi.h, y0 + bands.rows);
    const int e0 = std::max(0, y0 - bands.overlap), e1 = std::min(roi.h, y1 + bands.overlap);
    const Rect band{roi.x, roi.y + e0, roi.w, e1 - e0};
    DisparityMap part{ImageView<std::int16_t>(buf->data(), roi.w, band.h), band};
    auto r = matcher.match(in, band, p, part);
    if (!r) return r.error();
    for (int y = y0; y < y1; ++y)
      std::memcpy(out.q4.row(y), part.q4.row(y - e0), static_cast<std::size_t>(roi.w) * 2);
    const long expansions = total.expansions + r->expansions;
    const long skipped = total.expansions_skipped + r->expansions_skipped;
    const std::int64_t nodes = total.graph_nodes + r->graph_nodes;
    total = *r;
    total.expansions = static_cast<int>(expansions);
    total.expansions_skipped = static_cast<int>(skipped);
    total.graph_nodes = nodes;
  }
  out.roi = roi;
  total.matched_pixels = total.occluded_pixels = total.shadow_pixels = 0;
  for (int y = 0; y < roi.h; ++y)
    for (int x = 0; x < roi.w; ++x) {
      const bool shadow =
          (in.left_shadow != nullptr && in.left_shadow->is_shadow(roi.x + x, roi.y + y));
      if (is_valid_disparity(out.q4(x, y)))
        ++total.matched_pixels;
      else if (shadow)
        ++total.shadow_pixels;
      else
        ++total.occluded_pixels;
    }
  return total;
}

}  // namespace petra
