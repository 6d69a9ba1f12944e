// The rock: a convex polyhedron, the intersection of half-spaces
// normal.x <= offset (world frame, mm, outward unit normals). Holds each
// face's polygon and answers ray queries for the renderer.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "algo/core/result.hpp"
#include "sim/scene/polygon3.hpp"

namespace petra::sim {

struct HalfSpace {
  Eigen::Vector3d normal;   // unit, pointing out of the rock
  double offset_mm = 0;     // inside: normal.x <= offset
  bool grind_face = false;  // one of the designed large flat faces
};

struct RockFace {
  HalfSpace plane;
  Polygon3 polygon;  // the whole face (also the buried part), counter-clockwise seen from outside
};

struct ConvexRock {
  std::vector<RockFace> faces;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  // bounding sphere
  double radius_mm = 0;
};

// Faces of the intersection of the half-spaces. Planes that end up with no
// face (redundant) are dropped. Fails when the intersection is empty or not
// bounded within `extent_mm` of `around`.
Result<ConvexRock> make_convex_rock(const std::vector<HalfSpace>& planes,
                                    const Eigen::Vector3d& around, double extent_mm);

// Moves the rock by `shift` (offsets and polygons follow).
void translate_rock(ConvexRock& rock, const Eigen::Vector3d& shift);

// Where a ray origin + t*dir (t in [t_min, t_max]) enters the rock: face index
// and t, or face = -1 when it misses. The origin must lie outside the rock.
struct RockEntry {
  int face = -1;
  double t = 0;
};
RockEntry ray_enter_rock(const ConvexRock& rock, const Eigen::Vector3d& origin,
                         const Eigen::Vector3d& dir, double t_min, double t_max);

// True when the open segment origin + t*dir, t in (t_min, inf), meets the rock.
bool ray_meets_rock(const ConvexRock& rock, const Eigen::Vector3d& origin,
                    const Eigen::Vector3d& dir, double t_min);

// Polygon of face i above the ground plane z = 0 (empty when buried).
Polygon3 exposed_polygon(const RockFace& face);

}  // namespace petra::sim
