// Pictures an operator checks after `petra eval` (docs/icd.md):
//   disparity.png: the ROI's disparity, colour-mapped (blue far, red near),
//     black where there is no match, with a scale bar in px;
//   overlay.png: the flight overlay's colours (algo/chain/products: shadow, ground
//     and each accepted grind plane tinted, rock as seen), scaled, each
//     accepted plane marked by its rank at its centroid with a stroke along
//     its normal, the click (if any) as a cross, and a legend.
#pragma once

#include "algo/chain/pipeline.hpp"
#include "sim/io/image_io.hpp"

namespace petra::eval {

io::RgbImage disparity_picture(ConstDisparityMap map);
io::RgbImage overlay_picture(const PipelineOutput& out, const RectifiedPair& pair);

}  // namespace petra::eval
