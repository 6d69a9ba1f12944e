// planes.json (contract, docs/icd.md) from a reconstruction: the accepted
// grind planes, best first, the ground plane and the Table-1 statistics;
// per plane its verdict, uncertainty, footprint disc and
// the whole patch's own plane (optional fields).
#pragma once

#include <string>

#include "algo/camera/calib_check.hpp"
#include "algo/chain/reconstruction.hpp"

namespace petra::eval {

// The gray-level map a matcher applied to the right view (1/256 units).
struct GrayMapQ8 {
  int gain_q8 = 256;
  int offset_q8 = 0;
};

// `calibration`: the pair's calibration check, written when present (optional field);
// `gray_map`: the map the matcher applied (the DP's or the graph cut's), written when given.
std::string format_planes_json(const ReconstructionOutput& result,
                               const CalibCheck* calibration = nullptr,
                               const GrayMapQ8* gray_map = nullptr);

}  // namespace petra::eval
