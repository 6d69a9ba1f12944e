// Binary little-endian PLY of the reconstruction for MeshLab / CloudCompare:
// cloud.ply (vertices) and mesh.ply (vertices + triangles). Each vertex has
// x, y, z (float, mm, world frame of calib.json), red/green/blue (its class
// colour, products::class_colour: ground, rock, or the grind plane it
// supports) and gray (the left
// image's intensity there). docs/icd.md describes the layout.
#pragma once

#include <cstdint>
#include <string>

#include "algo/chain/reconstruction.hpp"
#include "algo/core/result.hpp"

namespace petra::eval {

// gray_of(i): intensity of point i.
std::string ply_bytes(const ReconstructionOutput& result, ConstGray8View left_rectified,
                      bool with_faces);
Status write_ply(const std::string& path, const ReconstructionOutput& result,
                 ConstGray8View left_rectified, bool with_faces);

}  // namespace petra::eval
