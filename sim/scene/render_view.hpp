// Renders what one camera of the rig sees, by casting rays through the exact
// Tsai model (pixel_to_ray) and integrating each pixel's square
// [i-0.5, i+0.5] x [j-0.5, j+0.5]: 2x2 samples where the pixel sees one
// surface, NxN (options.edge_supersampling) where a geometric edge (rock
// outline, facet edge, shadow edge) crosses it or a neighbour. Then sensor
// noise and 8-bit quantisation. Single-threaded and deterministic; a pixel's
// value does not depend on which window of the image is rendered.
#pragma once

#include <cstdint>

#include "sim/io/image_io.hpp"
#include "sim/scene/scene.hpp"

namespace petra::sim {

struct RenderedView {
  io::GrayImage image;        // 8-bit, with sensor noise
  io::GrayImage shadow_mask;  // 255 where over half the pixel is in shadow, else 0
  int edge_pixels = 0;        // pixels integrated with NxN samples
};

enum class Eye { left, right };

RenderedView render_view(const Scene& scene, Eye eye);
// Only the pixels inside `window` (clipped to the image); the rest stay 0.
RenderedView render_view(const Scene& scene, Eye eye, const Rect& window);

}  // namespace petra::sim
