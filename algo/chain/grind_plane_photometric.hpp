// Photometric refinement of the ranked grind planes (algo/surface/plane_photometric)
// after reconstruction: each plane's face pixels (the points labelled with
// its rank, border left out), its 3-D plane turned into the rectified
// disparity plane, refined on the gray levels of both images, and turned
// back. The normal turns by the refinement's rotation; the centroid (the
// grind point) moves as the face's plane under it does, keeping its standoff
// from that plane (the disc's surface on a curved face). Area, flatness, triangle
// count, verdicts and ranking stay those of the mesh.
// Inputs:  rectified pair geometry and images (right valid in right_valid),
//          the reconstruction output (pixels, vertex classes, planes).
// Output:  out.planes refined in place (accepted and rejected); how many of
//          the accepted planes were refined; per plane how its plane moved
//          (into moves; planes past its size are not recorded).
// Memory:  arena scratch of ROI area x (1 + sizeof(PixelPos)) + 8 x ROI height
//          bytes (grind_photometric_scratch_bytes), released.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <span>

#include "algo/chain/reconstruction.hpp"
#include "algo/core/arena.hpp"
#include "algo/surface/plane_photometric.hpp"

namespace petra {

// How the refinement moved one face's plane.
struct PlaneMove {
  bool refined = false;
  Eigen::Vector3d normal_before = Eigen::Vector3d::UnitZ();  // unit, the mesh's
  Eigen::Vector3d point_before = Eigen::Vector3d::Zero();    // on the plane before
  Eigen::Vector3d point_after = Eigen::Vector3d::Zero();     // the same pixel's point after
};

std::size_t grind_photometric_scratch_bytes(int roi_width, int roi_height);

Result<int> refine_grind_planes_photometric(const RectifiedPair& rect, ConstGray8View left,
                                            ConstGray8View right, Rect right_valid,
                                            const PhotometricPlaneParams& params,
                                            ReconstructionOutput& out, Arena& arena,
                                            std::span<PlaneMove> moves);

}  // namespace petra
