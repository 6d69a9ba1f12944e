// The rock under the operator's click, when no ground can be fitted (the rock
// fills the ROI, rocks stacked on rocks): region growing over the mesh from
// the clicked point. The mesh already has no triangle across a depth
// discontinuity (mesh_lift), so its edges carry depth continuity; an edge
// a -> b joins the region unless the surface folds inwards there:
//   - concave: |n_a - n_b| > sin(max_concave_step_deg) and
//     (n_a - n_b) . (x_a - x_b) <= 0, the normal turning inwards (where a
//     rock meets the ground or another rock, the surface turns concave; a
//     rock's own edges are convex, (n_a - n_b) . (x_a - x_b) > 0, and do not
//     stop the growth), or
//   - the normals differ by more than max_normal_step_deg between neighbours
//     (a fold or a spike at a depth edge).
// A point without a normal (zero vector, at the map's border or a hole) joins
// the region but is not grown from; the clicked point is, by depth continuity.
// Inputs: positions (mm), smoothed normals (unit, towards the cameras; zero:
// none), the mesh, the clicked point's index. Output: labels (rock = region,
// ground = the rest). Scratch from the arena (click_region_scratch_bytes),
// released on return. No heap.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <span>

#include "algo/core/arena.hpp"
#include "algo/core/result.hpp"
#include "algo/mesh/cloud.hpp"
#include "algo/mesh/delaunay.hpp"

namespace petra {

struct ClickRegionParams {
  double max_concave_step_deg = 2.0;  // per mesh edge (normals smoothed over a window)
  double max_normal_step_deg = 20.0;  // per mesh edge
  std::size_t min_points = 200;       // a region smaller is not a rock one can grind
  // The chain (algo/chain/reconstruction): a region holding less than this
  // share of the ROI's points is grown again with the concave limit doubled,
  // at most twice (a click in a shallow groove of the rock; the click path
  // runs only where the rock fills the ROI or rocks are stacked).
  double min_share = 0.05;
};

struct ClickRegionResult {
  std::size_t points = 0;           // in the region
  std::size_t stopped_concave = 0;  // edges refused as concave
  std::size_t stopped_fold = 0;     // edges refused for the normal step
  int loosened = 0;                 // times the chain doubled the concave limit (min_share)
};

Status validate(const ClickRegionParams& p);
std::size_t click_region_scratch_bytes(std::size_t points, std::size_t triangles);

Result<ClickRegionResult> grow_click_region(std::span<const Eigen::Vector3d> xyz_mm,
                                            std::span<const Eigen::Vector3d> normals,
                                            std::span<const MeshTriangle> mesh, std::size_t seed,
                                            const ClickRegionParams& params,
                                            std::span<PointClass> labels, Arena& arena);

}  // namespace petra
