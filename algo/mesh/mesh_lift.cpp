#include "algo/mesh/mesh_lift.hpp"

#include <Eigen/Geometry>
#include <cmath>

namespace petra {

Status validate(const MeshFilterParams& p) {
  if (!(p.max_edge_mm > 0.0) || !std::isfinite(p.max_edge_mm))
    return Error::make(Errc::invalid_argument, "mesh filter: max_edge_mm %.3g must be > 0",
                       p.max_edge_mm);
  if (!(p.max_view_angle_deg > 0.0) || p.max_view_angle_deg > 90.0)
    return Error::make(Errc::invalid_argument,
                       "mesh filter: max_view_angle_deg %.3g not in (0, 90]", p.max_view_angle_deg);
  return {};
}

TriangleGeometry triangle_geometry(std::span<const Eigen::Vector3d> xyz, const MeshTriangle& t) {
  const Eigen::Vector3d& a = xyz[static_cast<std::size_t>(t.v[0])];
  const Eigen::Vector3d& b = xyz[static_cast<std::size_t>(t.v[1])];
  const Eigen::Vector3d& c = xyz[static_cast<std::size_t>(t.v[2])];
  TriangleGeometry g;
  g.centroid_mm = (a + b + c) / 3.0;
  const Eigen::Vector3d cross = (b - a).cross(c - a);
  const double len = cross.norm();
  g.area_mm2 = 0.5 * len;
  g.normal = len > 0 ? Eigen::Vector3d(cross / len) : Eigen::Vector3d::Zero();
  return g;
}

Result<MeshFilterStats> remove_discontinuities(std::span<const Eigen::Vector3d> xyz,
                                               const Eigen::Vector3d& camera_centre,
                                               const MeshFilterParams& params,
                                               std::span<MeshTriangle> tris, Arena& scratch) {
  PETRA_TRY(validate(params));
  const std::int32_t npts = static_cast<std::int32_t>(xyz.size());
  for (std::size_t i = 0; i < tris.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      if (tris[i].v[k] < 0 || tris[i].v[k] >= npts)
        return Error::make(Errc::out_of_range, "mesh filter: triangle %zu vertex %d not in 0..%d",
                           i, tris[i].v[k], npts - 1);
      if (tris[i].n[k] < -1 || tris[i].n[k] >= static_cast<std::int64_t>(tris.size()))
        return Error::make(Errc::out_of_range, "mesh filter: triangle %zu neighbour %d", i,
                           tris[i].n[k]);
    }
  const double max_edge2 = params.max_edge_mm * params.max_edge_mm;
  const double cos_max = std::cos(params.max_view_angle_deg * M_PI / 180.0);
  const double cos2_max = cos_max * cos_max;
  MeshFilterStats stats;
  auto keep = [&](std::size_t i) {
    const MeshTriangle& t = tris[i];
    const Eigen::Vector3d& a = xyz[static_cast<std::size_t>(t.v[0])];
    const Eigen::Vector3d& b = xyz[static_cast<std::size_t>(t.v[1])];
    const Eigen::Vector3d& c = xyz[static_cast<std::size_t>(t.v[2])];
    if ((b - a).squaredNorm() > max_edge2 || (c - b).squaredNorm() > max_edge2 ||
        (a - c).squaredNorm() > max_edge2) {
      ++stats.removed_long;
      return false;
    }
    const Eigen::Vector3d cross = (b - a).cross(c - a);
    const double len2 = cross.squaredNorm();
    if (!(len2 > 0)) {
      ++stats.removed_degenerate;
      return false;
    }
    // |cos(normal, ray)| >= cos_max, squared: no root, no division.
    const Eigen::Vector3d ray = camera_centre - (a + b + c) / 3.0;
    const double dot = cross.dot(ray);
    if (!(dot * dot >= cos2_max * len2 * ray.squaredNorm())) {
      ++stats.removed_grazing;
      return false;
    }
    return true;
  };
  auto kept = keep_triangles(tris, keep, scratch);
  if (!kept) return kept.error();
  stats.kept = *kept;
  return stats;
}

}  // namespace petra
