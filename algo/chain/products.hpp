// The pictures of an evaluation, drawn once for the flight job's products
// (fsw/flight_pipeline_job) and for `petra eval`'s disparity.png and
// overlay.png (sim/eval, which scales them and adds its labels), in the one
// palette (algo/chain/palette.hpp); the PLY colours are class_colour.
//
// Inputs: a pipeline result (the ROI of the rectified left view, its shadow
// mask, the points' pixels and classes, the accepted planes).
// Outputs: caller buffers of the ROI's size: gray w x h, or interleaved RGB
// (an ImageView 3 * w wide).
// Memory: none beyond the caller's buffers. No heap.
#pragma once

#include <cstdint>

#include "algo/camera/rectify_geometry.hpp"
#include "algo/chain/palette.hpp"
#include "algo/chain/pipeline.hpp"
#include "algo/core/disparity.hpp"

namespace petra::products {

// Colour of a vertex class (kVertexGround, kVertexRock, kVertexPlane0 + rank).
palette::Rgb8 class_colour(std::uint8_t vertex_class);

// Smallest and largest valid Q4 disparity of the map; any = false when none.
struct DisparitySpan {
  std::int16_t lo_q4 = 0;
  std::int16_t hi_q4 = 0;
  bool any = false;
};
DisparitySpan disparity_span(ConstDisparityMap map);

// Disparity as 8-bit gray: 1..255 from the smallest to the largest match
// (linear in Q4), 0 where none (the flight DISPARITY product).
Status disparity_gray(ConstDisparityMap map, Gray8View out);

// Disparity on the palette's ramp, blue far to red near, linear in px between
// the smallest and the largest match; kNoData where none.
Status disparity_rgb(ConstDisparityMap map, ImageView<std::uint8_t> out_rgb);

// The overlay's colours: the rectified left ROI in gray, shadow tinted
// violet, then each point's pixel tinted by its class (ground, an accepted
// plane in its rank's colour); rock and refused candidates as seen. Tint:
// (gray + 2 colour) / 3.
Status overlay_classes(const PipelineOutput& p, ImageView<std::uint8_t> out_rgb);

// The flight OVERLAY product: overlay_classes, and each accepted plane's
// centroid as a white cross (13 px arms, 3 px wide).
Status overlay(const PipelineOutput& p, const RectifiedPair& pair, ImageView<std::uint8_t> out_rgb);

}  // namespace petra::products
