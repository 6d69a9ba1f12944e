// Reads planes.json (the grind planes contract, docs/icd.md): each plane's
// unit normal and centroid (world frame, mm), area and flatness, and the ground
// plane when present. Ground code: errors name the field; may allocate.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "algo/core/result.hpp"

namespace petra::sim {

struct GrindPlane {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  // unit, out of the rock
  Eigen::Vector3d centroid_mm = Eigen::Vector3d::Zero();
  double area_mm2 = 0.0;  // 0 when absent
  double rms_mm = 0.0;
};

struct PlanesFile {
  std::vector<GrindPlane> planes;         // best first
  std::optional<Eigen::Vector4d> ground;  // (normal, d_mm): n.x + d = 0
};

Result<PlanesFile> parse_planes_json(std::string_view text);

}  // namespace petra::sim
