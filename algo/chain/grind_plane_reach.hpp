// The footprint disc chosen again after the photometric refinement
// (grind_plane_photometric). The grind step chose each face's disc among the
// flat ones the arm reaches along the mesh's normal; the refinement then
// turns that normal (tenths of a degree, more on a steep face), and a disc at
// the edge of the arm's reach can leave it. ARM_GOTO plans on the refined
// plane, so a plane listed as reached at its disc (most_level, moved) whose
// grind point the arm no longer reaches along its refined normal has its
// disc chosen again over its face's triangles
// (mesh_class kVertexPlane0 + rank) by the same rules (algo/surface/
// grind_footprint: flatness, coverage, the most level disc the arm reaches)
// with the refined normal. The chosen disc's centre keeps its standoff from the
// face's plane as the refinement moved that plane, as the grind point does.
// The plane's 1-sigma, verdict and area stay the grind step's. A plane the
// arm reached at no flat disc along the mesh's normal stays none_reached
// (asking every flat disc again would double the worst case: one plan,
// about 55 us, per flat disc).
// Memory: footprint_again_scratch_bytes(mesh triangles), released. No heap.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <span>

#include "algo/chain/grind_plane_photometric.hpp"
#include "algo/chain/reconstruction.hpp"
#include "algo/core/arena.hpp"
#include "algo/surface/grind_footprint.hpp"
#include "algo/surface/grind_planes.hpp"

namespace petra {

std::size_t footprint_again_scratch_bytes(std::size_t triangles);

// moves[k]: plane k's move (out.planes.count of them); camera_mm: the left
// camera's centre (a moved grind point's view angle). Returns how many
// planes had their flat discs asked again.
Result<int> footprints_after_refinement(std::span<const PlaneMove> moves, const GrindParams& grind,
                                        const DiscReach& reach, const Eigen::Vector3d& camera_mm,
                                        ReconstructionOutput& out, Arena& arena);

}  // namespace petra
