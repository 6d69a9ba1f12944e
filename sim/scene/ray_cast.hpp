// Ray queries on a scene: what a viewing ray hits first (sky, ground, or a
// rock face), whether a point is in shadow, and the light it sends back.
#pragma once

#include <Eigen/Core>

#include "sim/scene/scene.hpp"

namespace petra::sim {

// Surface labels: sky, ground, then rock face i as kRockFace0 + i.
inline constexpr int kSky = 0;
inline constexpr int kGround = 1;
inline constexpr int kRockFace0 = 2;
// Stone k's face f (realistic world) as kStone0 + k * kStoneFaces + f.
inline constexpr int kStone0 = 1 << 20;
inline constexpr int kStoneFaces = 64;
// Neighbouring rock k's face f (options.neighbours) as kNeighbour0 + k * kNeighbourFaces + f.
inline constexpr int kNeighbour0 = 1 << 24;
inline constexpr int kNeighbourFaces = 256;

inline bool is_target_face(int surface) {
  return surface >= kRockFace0 && surface < kStone0;
}
inline bool is_stone(int surface) {
  return surface >= kStone0 && surface < kNeighbour0;
}
inline bool is_neighbour(int surface) {
  return surface >= kNeighbour0;
}
// Face index of rock `rock` (rock_at()'s index) a surface label is on, or -1.
inline int face_of_rock(int surface, int rock) {
  if (rock == 0) return is_target_face(surface) ? surface - kRockFace0 : -1;
  if (!is_neighbour(surface) || (surface - kNeighbour0) / kNeighbourFaces != rock - 1) return -1;
  return (surface - kNeighbour0) % kNeighbourFaces;
}

struct SceneHit {
  int surface = kSky;
  double t = 0;  // distance along the (unit) ray, mm
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
};

// First surface met by origin + t*dir, t > 0 (dir of unit length). The
// origin must be above the ground and outside the rock.
SceneHit trace(const Scene& scene, const Eigen::Vector3d& origin, const Eigen::Vector3d& dir);

// Outward unit normal of the surface at a hit (sky: zero).
Eigen::Vector3d surface_normal(const Scene& scene, const SceneHit& hit);

// In shadow: ground the rock hides from the sun (cast shadow), or a rock face
// turned away from the sun (self-shadow). The sky is never in shadow.
bool in_shadow(const Scene& scene, const SceneHit& hit);

// Radiance toward the camera along `dir`: albedo x (sun x cos(incidence) when
// lit + ambient sky light). `footprint_mm` is one pixel's size on the surface
// (texture detail below it is faded out).
double radiance(const Scene& scene, const SceneHit& hit, bool shadowed, double pixel_angle,
                const Eigen::Vector3d& dir);

}  // namespace petra::sim
