#include "sim/scene/ray_cast.hpp"

#include <algorithm>
#include <cmath>

namespace petra::sim {

namespace {

// The clean world: flat ground z = 0 and the planar rock.
SceneHit trace_clean(const Scene& scene, const Eigen::Vector3d& o, const Eigen::Vector3d& dir) {
  SceneHit hit;
  double t_max = INFINITY;
  if (dir.z() < 0) {
    t_max = -o.z() / dir.z();
    hit.surface = kGround;
    hit.t = t_max;
  }
  const RockEntry e = ray_enter_rock(scene.rock, o, dir, 0.0, t_max);
  if (e.face >= 0) {
    hit.surface = kRockFace0 + e.face;
    hit.t = e.t;
  }
  if (hit.surface != kSky) {
    hit.point = o + hit.t * dir;
    if (hit.surface == kGround) hit.point.z() = 0.0;  // exactly on the plane
  }
  return hit;
}

RockEntry enter_target(const Scene& scene, const Eigen::Vector3d& o, const Eigen::Vector3d& dir,
                       double t_min, double t_max) {
  return scene.face_relief.active
             ? ray_enter_rough_rock(scene.rock, scene.face_relief, o, dir, t_min, t_max)
             : ray_enter_rock(scene.rock, o, dir, t_min, t_max);
}

// Further rock k: rough faces of its own in a multi-rock scene, else a polyhedron.
RockEntry enter_neighbour(const Scene& scene, std::size_t k, const Eigen::Vector3d& o,
                          const Eigen::Vector3d& dir, double t_max) {
  if (k < scene.neighbour_relief.size() && scene.neighbour_relief[k].active)
    return ray_enter_rough_rock(scene.neighbours[k], scene.neighbour_relief[k], o, dir, 0.0, t_max);
  return ray_enter_rock(scene.neighbours[k], o, dir, 0.0, t_max);
}

// The realistic world: relief, rough faces, stones.
SceneHit trace_real(const Scene& scene, const Eigen::Vector3d& o, const Eigen::Vector3d& dir) {
  SceneHit hit;
  double t_max = INFINITY;
  if (scene.terrain.active) {
    double t = 0;
    if (ray_hits_terrain(scene.terrain, o, dir, 0.0, INFINITY, t)) {
      hit.surface = kGround;
      hit.t = t_max = t;
    }
  } else if (dir.z() < 0) {
    hit.surface = kGround;
    hit.t = t_max = -o.z() / dir.z();
  }
  const RockEntry e = enter_target(scene, o, dir, 0.0, t_max);
  if (e.face >= 0) {
    hit.surface = kRockFace0 + e.face;
    hit.t = t_max = e.t;
  }
  for (std::size_t k = 0; k < scene.stones.size(); ++k) {
    const RockEntry s = ray_enter_rock(scene.stones[k], o, dir, 0.0, t_max);
    if (s.face < 0) continue;
    hit.surface = kStone0 + static_cast<int>(k) * kStoneFaces + s.face;
    hit.t = t_max = s.t;
  }
  for (std::size_t k = 0; k < scene.neighbours.size(); ++k) {
    const RockEntry n = enter_neighbour(scene, k, o, dir, t_max);
    if (n.face < 0) continue;
    hit.surface = kNeighbour0 + static_cast<int>(k) * kNeighbourFaces + n.face;
    hit.t = t_max = n.t;
  }
  if (hit.surface != kSky) {
    hit.point = o + hit.t * dir;
    if (hit.surface == kGround && !scene.terrain.active) hit.point.z() = 0.0;
  }
  return hit;
}

bool any_meets(const std::vector<ConvexRock>& rocks, const Eigen::Vector3d& p,
               const Eigen::Vector3d& dir, int skip) {
  for (std::size_t k = 0; k < rocks.size(); ++k)
    if (static_cast<int>(k) != skip && ray_meets_rock(rocks[k], p, dir, 0.0)) return true;
  return false;
}

bool any_stone_meets(const Scene& scene, const Eigen::Vector3d& p, const Eigen::Vector3d& dir,
                     int skip) {
  return any_meets(scene.stones, p, dir, skip);
}

// Neighbour k's face f.
const RockFace& neighbour_face(const Scene& scene, int surface) {
  const int k = (surface - kNeighbour0) / kNeighbourFaces,
            f = (surface - kNeighbour0) % kNeighbourFaces;
  return scene.neighbours[static_cast<std::size_t>(k)].faces[static_cast<std::size_t>(f)];
}

}  // namespace

SceneHit trace(const Scene& scene, const Eigen::Vector3d& o, const Eigen::Vector3d& dir) {
  return clean_geometry(scene) ? trace_clean(scene, o, dir) : trace_real(scene, o, dir);
}

Eigen::Vector3d surface_normal(const Scene& scene, const SceneHit& hit) {
  if (hit.surface == kGround)
    return scene.terrain.active ? terrain_normal(scene.terrain, hit.point.x(), hit.point.y())
                                : Eigen::Vector3d::UnitZ();
  if (is_neighbour(hit.surface)) {
    const int k = (hit.surface - kNeighbour0) / kNeighbourFaces;
    const std::size_t kk = static_cast<std::size_t>(k);
    if (kk < scene.neighbour_relief.size() && scene.neighbour_relief[kk].active)
      return rough_face_normal(scene.neighbours[kk], scene.neighbour_relief[kk],
                               (hit.surface - kNeighbour0) % kNeighbourFaces, hit.point);
    return neighbour_face(scene, hit.surface).plane.normal;
  }
  if (hit.surface >= kStone0) {
    const int k = (hit.surface - kStone0) / kStoneFaces, f = (hit.surface - kStone0) % kStoneFaces;
    return scene.stones[static_cast<std::size_t>(k)]
        .faces[static_cast<std::size_t>(f)]
        .plane.normal;
  }
  if (hit.surface >= kRockFace0) {
    const int face = hit.surface - kRockFace0;
    if (scene.face_relief.active)
      return rough_face_normal(scene.rock, scene.face_relief, face, hit.point);
    return scene.rock.faces[static_cast<std::size_t>(face)].plane.normal;
  }
  return Eigen::Vector3d::Zero();
}

namespace {

// The realistic world's shadows: the target rock, the stones and the relief
// itself (a point whose own slope turns it from the sun is shadowed too).
bool in_shadow_real(const Scene& scene, const SceneHit& hit) {
  const Eigen::Vector3d& s = scene.sun_dir;
  if (hit.surface == kGround) {
    const Eigen::Vector3d n = surface_normal(scene, hit);
    if (n.dot(s) <= 0) return true;
    const Eigen::Vector3d p = hit.point + 0.01 * n;  // off the surface it starts on
    if (enter_target(scene, p, s, 0.0, INFINITY).face >= 0) return true;
    if (any_stone_meets(scene, p, s, -1)) return true;
    if (any_meets(scene.neighbours, p, s, -1)) return true;
    double t = 0;
    return scene.terrain.active && ray_hits_terrain(scene.terrain, p, s, 0.0, INFINITY, t);
  }
  if (is_neighbour(hit.surface)) {
    const int k = (hit.surface - kNeighbour0) / kNeighbourFaces;
    if (surface_normal(scene, hit).dot(s) <= 0) return true;
    const Eigen::Vector3d p = hit.point + 1e-3 * s;
    return enter_target(scene, hit.point, s, 1e-3, INFINITY).face >= 0 ||
           any_stone_meets(scene, p, s, -1) || any_meets(scene.neighbours, p, s, k);
  }
  if (hit.surface >= kStone0) {
    const int k = (hit.surface - kStone0) / kStoneFaces;
    if (surface_normal(scene, hit).dot(s) <= 0) return true;
    return enter_target(scene, hit.point, s, 1e-3, INFINITY).face >= 0 ||
           any_stone_meets(scene, hit.point + 1e-3 * s, s, k) ||
           any_meets(scene.neighbours, hit.point + 1e-3 * s, s, -1);
  }
  // A rock face: self-shadowed by its plane's orientation, or under a stone's
  // or a neighbour's shadow.
  const HalfSpace& h = scene.rock.faces[static_cast<std::size_t>(hit.surface - kRockFace0)].plane;
  return h.normal.dot(s) <= 0.0 || any_stone_meets(scene, hit.point, s, -1) ||
         any_meets(scene.neighbours, hit.point, s, -1);
}

}  // namespace

bool in_shadow(const Scene& scene, const SceneHit& hit) {
  if (hit.surface == kSky) return false;
  if (!clean_geometry(scene)) return in_shadow_real(scene, hit);
  if (hit.surface == kGround) return ray_meets_rock(scene.rock, hit.point, scene.sun_dir, 0.0);
  if (hit.surface >= kRockFace0) return surface_normal(scene, hit).dot(scene.sun_dir) <= 0.0;
  return false;
}

double radiance(const Scene& scene, const SceneHit& hit, bool shadowed, double pixel_angle,
                const Eigen::Vector3d& dir) {
  if (hit.surface == kSky) return scene.sky_radiance;
  const Eigen::Vector3d n = surface_normal(scene, hit);
  // Pixel footprint on the surface, stretched at grazing incidence.
  const double cos_view = std::max(std::abs(n.dot(dir)), 0.2);
  const double footprint = hit.t * pixel_angle / cos_view;
  const bool ground_like = hit.surface == kGround || is_stone(hit.surface);
  const TextureRecipe& recipe = ground_like ? scene.ground : scene.rock_surface;
  double a = scene.options.texture ? albedo(recipe, hit.point, footprint) : recipe.mean_albedo;
  if (is_stone(hit.surface))
    a *= scene.stone_albedo[static_cast<std::size_t>((hit.surface - kStone0) / kStoneFaces)];
  if (is_neighbour(hit.surface))
    a *= scene.neighbour_albedo[static_cast<std::size_t>((hit.surface - kNeighbour0) /
                                                         kNeighbourFaces)];
  // Sky light falls off on faces turned toward the ground.
  const double sky = scene.ambient * (0.7 + 0.3 * n.z());
  const double sun = shadowed ? 0.0 : std::max(0.0, n.dot(scene.sun_dir));
  return a * (sun + sky);
}

}  // namespace petra::sim
