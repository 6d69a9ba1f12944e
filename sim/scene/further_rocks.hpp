// Further rocks of a multi-rock scene: placement by kind.
#pragma once

#include "sim/scene/scene.hpp"

namespace petra::sim {

// Multi-rock scenes (options.rocks >= 2, docs/scene.md "Several rocks"):
// adds options.rocks - 1 further rocks to a placed scene as neighbours, rock
// k of the kind (seed + k) mod kRockKinds, each drawn from the rock generator
// at a ground point seen in the left image (or slid against a placed rock
// until it touches), kept only when it lies in both views, overlaps no
// rock, hides no facet of another rock nor is hidden by one, and its
// judged facets (scene_rocks.hpp) are of its kind. Fails when one finds no
// place; the caller then draws the target again.
Status add_rocks(Scene& scene);

}  // namespace petra::sim
