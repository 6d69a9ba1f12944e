// The proposals picture (PRODUCT kind 5): the left image, subsampled by
// `step` and staged as RGB by the ProductStreamer, with each proposal drawn
// on it: its ROI as a 2 px frame in its rank's colour (algo/chain/palette:
// rank 1 is plane colour 0) and its click as a cross; a proposal that offers
// no plane is framed in the palette's grey for refused faces, dashed. Labels
// are the ground's (it has the packet). Memory: none; no heap.
#pragma once

#include "algo/core/image_view.hpp"
#include "algo/propose/proposals.hpp"

namespace petra::fsw {

// rgb: interleaved RGB, 3 * w bytes wide; coordinates are divided by step.
void draw_proposals(ImageView<std::uint8_t> rgb, int step, const ProposalList& list);

}  // namespace petra::fsw
