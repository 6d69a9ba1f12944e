// planes.json (contract, docs/icd.md) from a reconstruction: the accepted
// grind planes, best first, the ground plane and the Table-1 statistics;
// per plane its verdict, uncertainty, footprint disc and
// the whole patch's own plane (optional fields).
#pragma once

#include <string>

#include "algo/reconstruction.hpp"

namespace petra::eval {

std::string format_planes_json(const ReconstructionOutput& result);

}  // namespace petra::eval
