// Rough, slightly curved rock faces (docs/scene.md "Realistic world"). Face i
// of the polyhedron n.x <= d is replaced by n.x <= d - s_i(x), the depth
// s_i >= 0 being a bulge (curvature / 2 x squared distance from the face's
// exposed centroid, so the face is highest in its middle) plus a solid
// fractal roughness (wavelengths 2.5..20 mm, the chosen RMS). The rock is the
// intersection of these displaced half-spaces, inside the polyhedron, so a
// ray is clipped against the polyhedron first and then sphere-traced.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "sim/scene/convex_rock.hpp"
#include "sim/scene/scene_options.hpp"
#include "sim/scene/texture.hpp"

namespace petra::sim {

struct FaceRelief {
  bool active = false;     // false: the faces are exact planes
  double rough_scale = 0;  // multiplies the unit-RMS fractal
  double rough_floor = 0;  // added so the depth stays >= 0
  double curvature_per_mm = 0;
  std::vector<Eigen::Vector3d> bulge_centre;  // per face
  double max_depth_mm = 0;
  double lipschitz = 0;  // bound on |grad s|
  Permutation perm{};
};

// Relief for `rock`'s faces (bulge centres: the exposed polygons' centroids).
FaceRelief make_face_relief(const World& world, std::uint64_t seed, const ConvexRock& rock);

// The seed's unit fractal (its permutation, RMS, peak and steepest slope,
// measured on samples): what make_face_relief measures, for reuse over the
// rocks of one scene.
struct FractalStats {
  Permutation perm{};
  double rms = 1, v_max = 0, grad_max = 0;
};
FractalStats fractal_stats(std::uint64_t seed);
FaceRelief make_face_relief(const World& world, const FractalStats& stats, const ConvexRock& rock);

// Depth s_i(x) of face i below its plane at x (mm, >= 0).
double face_depth(const FaceRelief& relief, int face, const HalfSpace& plane,
                  const Eigen::Vector3d& x);

// Where origin + t*dir (t in [t_min, t_max]) enters the rough rock.
RockEntry ray_enter_rough_rock(const ConvexRock& rock, const FaceRelief& relief,
                               const Eigen::Vector3d& origin, const Eigen::Vector3d& dir,
                               double t_min, double t_max);

// Outward unit normal of face i's rough surface at x.
Eigen::Vector3d rough_face_normal(const ConvexRock& rock, const FaceRelief& relief, int face,
                                  const Eigen::Vector3d& x);

}  // namespace petra::sim
