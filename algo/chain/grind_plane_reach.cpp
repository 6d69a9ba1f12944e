#include "algo/chain/grind_plane_reach.hpp"

#include <algorithm>
#include <cstddef>

namespace petra {

namespace {

// The face's triangles (mesh class `cls`) as footprint samples.
std::size_t face_samples(const ReconstructionOutput& out, std::uint8_t cls,
                         const Eigen::Vector3d& camera, std::span<FaceSample> samples) {
  std::size_t m = 0;
  for (std::size_t i = 0; i < out.mesh.size() && m < samples.size(); ++i)
    if (out.mesh_class[i] == cls) samples[m++] = triangle_sample(out.xyz_mm, out.mesh[i], camera);
  return m;
}

// A point of the mesh's disc moved with the face's plane: the same standoff
// from the refined plane as from the mesh's, at the same place along it.
Eigen::Vector3d moved_with_plane(const Eigen::Vector3d& c, const PlaneMove& move,
                                 const Eigen::Vector3d& refined_normal) {
  const double standoff = move.normal_before.dot(c - move.point_before);
  return c - refined_normal.dot(c - move.point_after) * refined_normal + standoff * refined_normal;
}

// Plane k's disc chosen again with its refined normal; true when it was.
Result<bool> choose_again(const PlaneMove& move, std::uint8_t cls, const GrindParams& grind,
                          const DiscReach& reach, const Eigen::Vector3d& camera,
                          const ReconstructionOutput& out, Arena& arena, GrindPlane& plane) {
  ArenaScope scope(arena);
  auto samples = arena.allocate<FaceSample>(out.mesh.size(), "footprint again samples");
  if (!samples) return samples.error();
  const std::size_t m = face_samples(out, cls, camera, *samples);
  if (m < 3) return false;
  FootprintParams fp;
  fp.diameter_mm = grind.grinder_diameter_mm;
  fp.min_coverage = grind.min_footprint_coverage;
  fp.max_rms_mm = grind.max_footprint_rms_mm;
  fp.reach = &reach;
  auto f = find_footprint(samples->first(m), plane.normal, move.point_after, fp, arena);
  if (!f) return f.error();
  if (!f->covered || f->reach == FootprintReach::not_asked) return false;
  plane.footprint_reach = f->reach;
  if (f->reach == FootprintReach::none_reached) return true;  // the disc stays; reach says why
  plane.centroid_mm = moved_with_plane(f->centre_mm, move, plane.normal);
  plane.footprint_rms_mm = f->rms_mm;
  plane.footprint_pv_mm = f->peak_to_valley_mm;
  plane.footprint_coverage = f->coverage;
  plane.footprint_normal = f->normal;
  plane.view_angle_deg = plane_view_angle_deg(plane.normal, plane.centroid_mm, camera);
  return true;
}

}  // namespace

std::size_t footprint_again_scratch_bytes(std::size_t triangles) {
  return arena_bytes_for<FaceSample>(triangles) + footprint_scratch_bytes(triangles) +
         alignof(std::max_align_t);
}

Result<int> footprints_after_refinement(std::span<const PlaneMove> moves, const GrindParams& grind,
                                        const DiscReach& reach, const Eigen::Vector3d& camera_mm,
                                        ReconstructionOutput& out, Arena& arena) {
  int again = 0;
  const int n = std::min(out.planes.count, static_cast<int>(moves.size()));
  for (int k = 0; k < n; ++k) {
    GrindPlane& plane = out.planes.planes[k];
    // Only a disc listed as reached is asked about again: one the arm
    // reached nowhere along the mesh's normal stays listed so, without
    // another plan per flat disc (up to 256 of them).
    const bool listed_reached = plane.footprint_reach == FootprintReach::most_level ||
                                plane.footprint_reach == FootprintReach::moved;
    if (!moves[k].refined || !listed_reached || reach.reaches(plane.centroid_mm, plane.normal))
      continue;
    auto chosen = choose_again(moves[k], static_cast<std::uint8_t>(kVertexPlane0 + k), grind, reach,
                               camera_mm, out, arena, plane);
    if (!chosen) return chosen.error();
    again += *chosen ? 1 : 0;
  }
  return again;
}

}  // namespace petra
