#include "sim/scene/ray_cast.hpp"

#include <algorithm>
#include <cmath>

namespace petra::sim {

SceneHit trace(const Scene& scene, const Eigen::Vector3d& o, const Eigen::Vector3d& dir) {
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

Eigen::Vector3d surface_normal(const Scene& scene, const SceneHit& hit) {
  if (hit.surface == kGround) return Eigen::Vector3d::UnitZ();
  if (hit.surface >= kRockFace0)
    return scene.rock.faces[static_cast<std::size_t>(hit.surface - kRockFace0)].plane.normal;
  return Eigen::Vector3d::Zero();
}

bool in_shadow(const Scene& scene, const SceneHit& hit) {
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
  const TextureRecipe& recipe = hit.surface == kGround ? scene.ground : scene.rock_surface;
  const double a =
      scene.options.texture ? albedo(recipe, hit.point, footprint) : recipe.mean_albedo;
  // Sky light falls off on faces turned toward the ground.
  const double sky = scene.ambient * (0.7 + 0.3 * n.z());
  const double sun = shadowed ? 0.0 : std::max(0.0, n.dot(scene.sun_dir));
  return a * (sun + sky);
}

}  // namespace petra::sim
