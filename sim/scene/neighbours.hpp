// Neighbouring rocks that touch the target rock (docs/scene.md "Realistic
// world", `--neighbours N`): full-size convex rocks from the same generator,
// 0.5..1.0 x the target's size, slid along the ground toward the target
// until their parts above the ground touch it, then slid back 0..kMaxNeighbourGapMm,
// beside or behind it as the cameras see it, never in front of a grind face.
// They cast and receive shadows and appear in the disparity truth, but are
// never truth facets.
#pragma once

#include <Eigen/Core>

#include "sim/scene/scene.hpp"

namespace petra::sim {

inline constexpr double kMaxNeighbourGapMm = 1.5;

// Adds options.neighbours rocks to a placed scene (before the stones). Fails
// when no placement is found that leaves the grind faces in view of both
// cameras; the caller then tries another placement of the target.
Status add_neighbours(Scene& scene);

// True when a point of the target's grind faces (sampled every ~step_mm) is
// hidden from either camera by `other`.
bool hides_grind_face(const Scene& scene, const ConvexRock& other, double step_mm);

}  // namespace petra::sim
