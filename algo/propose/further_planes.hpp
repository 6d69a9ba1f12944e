// A rock's further flat faces from its own chain run (issue 26;
// docs/proposals.md 2). The chain at c = 3 clusters a rock's normals into
// cluster_count(3) = 6 classes and keeps the faces its qualification accepts;
// a rounded rock's tangent facets, each flat as rendered, are merged into a
// neighbouring class there or left under the area and footprint checks. The
// further pass clusters again, with the chain's own grind-plane step and
// checks (algo/chain/reconstruction grind_planes_on_mesh: area, footprint
// flatness, view angle, 1-sigma), on the triangles of the same run's mesh
// that lie on this rock (detection's rock map) and that no plane the
// proposal keeps already explains; a plane of the same face as a kept one
// (the chain's merge rule) is left out. The first planes of the proposal stay
// the chain's: the pass only fills the slots they leave.
// Memory: the arena past the chain run's outputs (one byte per mesh triangle
// + grind_planes_on_mesh_bytes), released on return; no heap.
#pragma once

#include <cstdint>
#include <span>

#include "algo/chain/reconstruction.hpp"
#include "algo/core/arena.hpp"
#include "algo/core/result.hpp"
#include "algo/propose/rock_detection.hpp"

namespace petra {

// Where a rock lies in detection's rock map (algo/propose/rock_detection).
struct RockOnMap {
  std::span<const std::uint8_t> map;
  int map_width = 0;
  int cell_px = 1;  // rectified pixels per cell side
  int index = 0;    // the rock's value in the map
  // The map's value at rectified pixel (u, v); kNoRock outside the map.
  std::uint8_t at(double u, double v) const;
  // Whether the mesh triangle's centre pixel (its vertices' mean) lies on the rock.
  bool holds(const ReconstructionOutput& r, const MeshTriangle& t) const;
};

// Per plane k of the run (vertex_class kVertexPlane0 + k), whether more than
// half its vertices lie on the rock's cells (not on another rock's, the
// ground's or none). A plane the proposer adds past the chain's accepted
// ones must; the chain's own rule (planes_on_other_rocks) lets ground votes
// pass.
void planes_mostly_on(const ReconstructionOutput& r, const RockOnMap& rock,
                      bool (&on)[kMaxClasses]);

// The further pass (c classes asked; cluster_count(c) clustered) on the run
// `r` (made with rig, rect and params) for the rock, leaving out the
// triangles of the chain's planes marked in `explained` (by rank). Its
// planes ranked as the chain ranks them; none (count 0) when fewer than 3c
// triangles are left. reach: the arm's (find_grind_planes).
Result<GrindResult> further_planes(const StereoRig& rig, const RectifiedPair& rect,
                                   const ReconstructionParams& params,
                                   const ReconstructionOutput& r, const RockOnMap& rock,
                                   const bool (&explained)[kMaxClasses], int c,
                                   const DiscReach* reach, Arena& arena);

// Whether two reported planes are one face by the chain's merge rule
// (same_plane on their normals and centroids).
bool same_face(const GrindPlane& a, const GrindPlane& b, const GrindParams& p);

}  // namespace petra
