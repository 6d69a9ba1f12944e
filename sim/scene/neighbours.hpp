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

// The placement machinery, shared with the multi-rock scenes (further_rocks.hpp).
// True when the parts of a and b above the ground z = 0 share a volume.
bool overlap_above_ground(const ConvexRock& a, const ConvexRock& b);
// Slide along -dir (horizontal, unit) that brings b into first contact with
// a: the smallest s with b - s dir overlapping a, or a negative value when b
// never meets a within `reach`.
double contact_slide(const ConvexRock& a, const ConvexRock& b, const Eigen::Vector3d& dir,
                     double reach);

// True when a point of the target's grind faces (sampled every ~step_mm) is
// hidden from either camera by `other`.
bool hides_grind_face(const Scene& scene, const ConvexRock& other, double step_mm);

}  // namespace petra::sim
