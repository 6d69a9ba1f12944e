// planes.json (contract, docs/icd.md) from a reconstruction: the accepted
// grind planes, best first, the ground plane and the Table-1 statistics;
// per plane its verdict, uncertainty, footprint disc and
// the whole patch's own plane (optional fields).
#pragma once

#include <string>

#include "algo/camera/calib_check.hpp"
#include "algo/chain/reconstruction.hpp"
#include "algo/stereo/match_dp.hpp"

namespace petra::eval {

// `calibration`: the pair's calibration check, written when present (optional field);
// `match`: the DP matcher's statistics, whose gray-level map is written when given.
std::string format_planes_json(const ReconstructionOutput& result,
                               const CalibCheck* calibration = nullptr,
                               const MatchDpStats* match = nullptr);

}  // namespace petra::eval
