// A rock's flat faces found by the grinder's disc, not by the clustering
// (issue 26; docs/proposals.md 2). The chain's clustering decides how many
// faces it sees: a rounded rock's tangent facets, each flat as rendered, are
// merged into a neighbouring class or split into fragments under the area
// check. Here the tool itself looks:
//   1. the run's rock triangles on this rock's cells (detection's rock map)
//      that no kept plane of the chain explains (on its patch and within
//      explained_band_mm of its plane) are the free ones;
//   2. seeds: a regular stride through them, at most max_seeds (bounded
//      work);
//   3. per seed, the free triangles whose centroids lie within the tool's
//      radius of it: their area-weighted plane, then the disc of that plane
//      (within the radius along the plane, within band_mm of it) refitted;
//      the disc is flat when its RMS is within the footprint tolerance and
//      its triangles cover the chain's min_footprint_coverage of the disc;
//   4. the flat discs, flattest first (a disc across a shallow crease is
//      flat within the tolerance, less so than the faces' own discs), each
//      seed inside an earlier face skipped: a flat disc on a plane the proposal keeps (the chain's
//      merge rule, same_face) marks its triangles explained; else it joins the face whose first
//      disc's plane it shares (the same rule), or starts one (at most 32); its free triangles not
//      yet on a face join it;
//   5. per face of at least min_discs discs: its plane (area-weighted), the
//      face grown over the mesh's edges to free triangles within 3 RMS of
//      that plane, refitted (normal towards the camera), then the chain's own
//      checks (algo/surface/grind_qualify: footprint, flatness, coverage,
//      view angle, 1-sigma) and a footprint RMS within max_footprint_rms_mm;
//      ranked accepted by area, then the rest, at most kMaxClasses.
// Memory: flat_discs_bytes(triangles, max_seeds) from the arena, released on return
// (less than the further pass's grind scratch it follows); no heap.
#pragma once

#include <cstddef>
#include <span>

#include "algo/chain/reconstruction.hpp"
#include "algo/core/arena.hpp"
#include "algo/core/result.hpp"
#include "algo/propose/further_planes.hpp"

namespace petra {

struct FlatDiscParams {
  int max_seeds = 256;   // discs tried per rock (bounded work)
  double band_mm = 3.0;  // a disc's triangles lie this near its plane
  int min_discs = 3;     // flat discs on a face before it is qualified
  // A triangle of a kept plane's patch is explained when it lies this near
  // the plane: the chain's regrowth takes a tangent facet's triangles into
  // its neighbour's patch, off that patch's plane.
  double explained_band_mm = 1.5;
  // A face found here is offered when its footprint disc is this flat (the
  // chain's tolerance is 1 mm): on the multi-rock set the faces offered at
  // 0.57..0.76 mm lay on facets the truth calls too rough (1.1..1.2 mm
  // rendered) or too small, those at 0.40..0.52 on targets (docs/proposals.md 5).
  double max_footprint_rms_mm = 0.55;
};
Status validate(const FlatDiscParams& p);

std::size_t flat_discs_bytes(std::size_t triangles, int max_seeds);

// The faces (GrindResult: planes accepted first, by area; `accepted` of
// them) on the free triangles of the run `r` (made with rig, rect and
// params) on the rock, leaving out the chain's planes marked in
// `explained` (by rank); a flat disc on a `kept` plane (the chain's merge
// rule) starts no face. None when no disc is flat. reach: the arm's
// (find_grind_planes).
Result<GrindResult> flat_discs(const StereoRig& rig, const RectifiedPair& rect,
                               const ReconstructionParams& params, const ReconstructionOutput& r,
                               const RockOnMap& rock, const bool (&explained)[kMaxClasses],
                               std::span<const GrindPlane> kept, const FlatDiscParams& discs,
                               const DiscReach* reach, Arena& arena);

}  // namespace petra
