// The 2-D Delaunay mesh lifted to 3-D with the same connectivity (docs/method.md 3d),
// minus the triangles that span depth discontinuities (a rock's silhouette
// against the ground, the rim of a shadow hole): a triangle goes when
//   - any 3-D edge is longer than max_edge_mm (bridges a hole), or
//   - its normal makes more than max_view_angle_deg with the viewing ray from
//     the left camera centre to its centroid (a real surface that steep is
//     seen too obliquely to measure; a step between depths always is).
// Inputs: point positions (mm), the camera centre (world, mm), the triangles
// from delaunay_triangulate. Output: the kept triangles compacted in place,
// neighbours re-indexed (-1 where the neighbour was removed). Scratch: 4 bytes
// per triangle from the arena, released on return. No heap.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <span>

#include "algo/core/arena.hpp"
#include "algo/core/result.hpp"
#include "algo/mesh/delaunay.hpp"

namespace petra {

struct MeshFilterParams {
  double max_edge_mm = 25.0;         // > 0
  double max_view_angle_deg = 80.0;  // (0, 90]
};

struct MeshFilterStats {
  std::size_t kept = 0;
  std::size_t removed_long = 0;        // an edge longer than max_edge_mm
  std::size_t removed_grazing = 0;     // seen more obliquely than max_view_angle_deg
  std::size_t removed_degenerate = 0;  // zero area in 3-D
};

Status validate(const MeshFilterParams& p);

inline std::size_t mesh_filter_scratch_bytes(std::size_t triangles) {
  return arena_bytes_for<std::int32_t>(triangles);
}

// Keeps the triangles with keep(i) true (i: index before compaction), in
// order, in place; neighbours re-indexed, -1 where the neighbour went.
// Scratch: mesh_filter_scratch_bytes(triangles.size()). Returns the count kept.
template <class Keep>
Result<std::size_t> keep_triangles(std::span<MeshTriangle> tris, Keep&& keep, Arena& scratch) {
  ArenaScope scope(scratch);
  auto remap = scratch.allocate<std::int32_t>(tris.size(), "triangle index map");
  if (!remap) return remap.error();
  std::size_t kept = 0;
  for (std::size_t i = 0; i < tris.size(); ++i)
    (*remap)[i] = keep(i) ? static_cast<std::int32_t>(kept++) : -1;
  for (std::size_t i = 0; i < tris.size(); ++i) {
    const std::int32_t r = (*remap)[i];
    if (r < 0) continue;
    MeshTriangle t = tris[i];
    for (int k = 0; k < 3; ++k)
      t.n[k] = t.n[k] < 0 ? -1 : (*remap)[static_cast<std::size_t>(t.n[k])];
    tris[static_cast<std::size_t>(r)] = t;  // r <= i: never overwrites an unread entry
  }
  return kept;
}

// `triangles` is rewritten: the first stats.kept entries are the kept mesh.
Result<MeshFilterStats> remove_discontinuities(std::span<const Eigen::Vector3d> xyz_mm,
                                               const Eigen::Vector3d& camera_centre_mm,
                                               const MeshFilterParams& params,
                                               std::span<MeshTriangle> triangles, Arena& scratch);

// Unit normal (A-B x A-C order, i.e. (B-A) x (C-A)) and area of a triangle.
struct TriangleGeometry {
  Eigen::Vector3d centroid_mm;
  Eigen::Vector3d normal;  // unit; zero when the area is zero
  double area_mm2 = 0;
};
TriangleGeometry triangle_geometry(std::span<const Eigen::Vector3d> xyz_mm, const MeshTriangle& t);

}  // namespace petra
