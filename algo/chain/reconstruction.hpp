// From a rectified disparity map to ranked grind planes, the back half of
// the onboard chain (docs/method.md 3c, 3d, 2a, 4):
//   mean filter -> triangulate (eq. 8) -> Delaunay (rectified left pixels)
//   -> lift and drop discontinuities -> surface normals (local disparity
//   planes) -> rock/ground segmentation: the ground plane (ground_segment),
//   or, when there is no ground and the operator clicked, the rock grown
//   from the click over the mesh (click_region) -> rock triangles
//   -> C-means + angle clustering -> ranked grind planes.
// Every buffer comes from the caller's arena: outputs (cloud, mesh, labels,
// filtered map) stay allocated for the caller to read or downlink until it
// resets the arena; scratch of each step is released after it.
// reconstruction_arena_bytes(budget) is the whole need for a budget: an
// arena that size never runs out for inputs within the budget.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "algo/camera/camera_model.hpp"
#include "algo/camera/rectify_geometry.hpp"
#include "algo/core/arena.hpp"
#include "algo/core/disparity.hpp"
#include "algo/core/result.hpp"
#include "algo/core/step_clock.hpp"
#include "algo/mesh/cloud.hpp"
#include "algo/mesh/delaunay.hpp"
#include "algo/mesh/disparity_filter.hpp"
#include "algo/mesh/mesh_lift.hpp"
#include "algo/mesh/surface_normals.hpp"
#include "algo/surface/click_region.hpp"
#include "algo/surface/grind_planes.hpp"
#include "algo/surface/ground_normals.hpp"
#include "algo/surface/ground_segment.hpp"
#include "algo/surface/support_surface.hpp"

namespace petra {

struct ReconstructionBudget {
  int max_roi_width = 512;         // px, of the disparity map
  int max_roi_height = 512;        // px
  std::size_t max_points = 65536;  // 3-D points; more valid disparities: taken on a pixel stride
};
Status validate(const ReconstructionBudget& b);
std::size_t reconstruction_arena_bytes(const ReconstructionBudget& b);

struct ReconstructionParams {
  MeanFilterParams filter;
  NormalParams normals;
  MeshFilterParams mesh;
  GroundParams ground;
  GroundNormalParams ground_normals;
  ClickRegionParams click_region;
  SupportParams support;  // click_region: a plane on the surface the rock stands on
  GrindParams grind;
};

// How the rock was told from its surroundings (planes.json "segmentation",
// EVAL_RESULT.segmentation).
enum class SegmentMethod : std::uint8_t {
  ground_plane = 0,  // rock = what stands above the fitted ground plane
  click_region = 1,  // no ground: rock = the region grown from the click
};
const char* segment_method_name(SegmentMethod m);

struct ReconstructionRequest {
  int planes = 2;                    // c, from the operator
  ClickPx click;                     // rectified left pixel, optional
  const DiscReach* reach = nullptr;  // the arm's, when known (find_grind_planes)
};

// Per-vertex class for products (cloud/mesh colouring).
inline constexpr std::uint8_t kVertexGround = 0;
inline constexpr std::uint8_t kVertexRock = 1;
inline constexpr std::uint8_t kVertexPlane0 = 2;  // + rank of the grind plane

struct ReconstructionStats {
  double disparity_min_px = 0, disparity_max_px = 0;  // of the input map
  long dense_points = 0;                              // valid disparities in (paper: 23465)
  long filtered_points = 0;                           // after the mean filter (paper: 21382)
  int point_stride = 1;  // 3-D points on every s-th pixel and row: more valid than max_points
  std::size_t triangulated = 0, triangulation_rejected = 0;
  std::size_t delaunay_triangles = 0, duplicates = 0;
  MeshFilterStats mesh;
  std::size_t rock_triangles = 0;
};

struct ReconstructionOutput {
  // Cloud (structure of arrays, `points` long).
  std::span<Eigen::Vector3d> xyz_mm;
  std::span<PixelPos> pixels;
  std::span<PointClass> point_class;
  std::span<Eigen::Vector3d> normals;    // smoothed surface normal per point (zero: none)
  std::span<std::uint8_t> vertex_class;  // kVertexGround / kVertexRock / kVertexPlane0 + k
  // Mesh after discontinuity removal (all of it, rock and ground).
  std::span<MeshTriangle> mesh;
  std::span<std::uint8_t> mesh_class;  // as vertex_class, per triangle
  DisparityMap filtered;
  GroundResultT<double> ground;  // click_region: plane of the points around the rock
  SegmentMethod segmentation = SegmentMethod::ground_plane;
  ClickRegionResult click_region;  // when segmentation == click_region
  // click_region: planes found on the surface the rock stands on (support_surface),
  // their points dropped from the rock and the planes found again.
  int support_planes = 0;
  std::size_t support_points = 0;
  GrindResult planes;
  ReconstructionStats stats;
};

Result<ReconstructionOutput> reconstruct(const StereoRig& rig, const RectifiedPair& rect,
                                         ConstDisparityMap disparity,
                                         const ReconstructionRequest& request,
                                         const ReconstructionParams& params,
                                         const ReconstructionBudget& budget, Arena& arena,
                                         const StepClock& clock, StepTimings& timings);

// Grind planes (find_grind_planes, c planes, the chain's grind parameters
// and rig) on the triangles of out.mesh marked in triangle_plane (one byte
// per triangle; in: nonzero = taken; out: the index of the plane whose patch
// holds it, 0..count-1 in rank order, 0xFF none). The chain's own step takes
// every rock triangle; the proposer takes a rock's triangles that no accepted
// plane explains (algo/propose/further_planes). Scratch from the arena:
// grind_planes_on_mesh_bytes(out.mesh.size()), released on return.
std::size_t grind_planes_on_mesh_bytes(std::size_t triangles);
// reach: the arm's, or none (find_grind_planes).
Result<GrindResult> grind_planes_on_mesh(const StereoRig& rig, const RectifiedPair& rect,
                                         const ReconstructionOutput& out, int c,
                                         const ReconstructionParams& params, Arena& arena,
                                         std::span<std::uint8_t> triangle_plane,
                                         const DiscReach* reach);

}  // namespace petra
