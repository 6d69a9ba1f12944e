// The graph-cut matcher over horizontal bands of the ROI, so its memory grows
// with the ROI's width times a band's rows instead of with the whole ROI
// (about 200 B per pixel: a 512 x 384 ROI would need 39 MB whole).
// Each band of `rows` rows is matched with `overlap` more rows above and
// below (the smoothness term and the DP start see past the band's edge) and
// only its own rows are kept. Bands are separate problems sharing one
// automatic K (the row-weighted mean of the bands' own, so the whole image's
// to within a unit) and the lambdas it gives; each has its own DP start and
// expansion order (docs/graphcut.md, "Bands", has the effect on accuracy). A ROI no taller than
// rows + 2 * overlap is matched whole, exactly as GraphCutMatcher does.
// Memory: graph_cut_bands_bytes() from the caller's arena, released on return.
#pragma once

#include <cstddef>

#include "algo/core/arena.hpp"
#include "algo/core/result.hpp"
#include "algo/stereo/match_graphcut.hpp"

namespace petra {

struct GraphCutBands {
  int rows = 0;      // rows kept per band; 0: the whole ROI in one band
  int overlap = 16;  // extra rows matched above and below each band
};

// Rows of the largest problem a band poses for a ROI of max_height rows.
int graph_cut_band_height(int max_height, GraphCutBands bands);
std::size_t graph_cut_bands_bytes(const GraphCutBudget& budget, GraphCutBands bands);

// As GraphCutMatcher::match (start: dp, block_matching or occluded; a given
// start map is refused when the ROI is split). The report sums the work
// counters (expansions, graph nodes) and recounts the pixels over the ROI;
// energies are those of the last band.
Result<GraphCutReport> match_graph_cut_bands(const StereoInput& in, Rect roi,
                                             const GraphCutParams& params, GraphCutBands bands,
                                             Arena& arena, DisparityMap& out);

}  // namespace petra
