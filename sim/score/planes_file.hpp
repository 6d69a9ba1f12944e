// planes.json (contract, docs/icd.md): the grind planes a reconstruction
// found, in the world frame of calib.json, best first. Required: planes
// (each with normal and centroid_mm; area_mm2, rms_mm, triangles are read
// when present). ground and stats are optional for scoring.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string_view>
#include <vector>

#include "algo/core/result.hpp"

namespace petra::sim {

struct OutputPlane {
  Eigen::Vector3d normal;  // unit, out of the rock
  Eigen::Vector3d centroid_mm;
  // Where the grinder goes (optional field; the face's centroid when absent).
  std::optional<Eigen::Vector3d> grind_point_mm;
  const Eigen::Vector3d& grind_point() const {
    return grind_point_mm ? *grind_point_mm : centroid_mm;
  }
  double area_mm2 = 0;
  double rms_mm = 0;
  long long triangles = 0;
};

struct GroundPlane {
  Eigen::Vector3d normal;  // unit
  double d_mm = 0;         // normal.X + d = 0
};

struct PlanesFile {
  std::vector<OutputPlane> planes;
  std::optional<GroundPlane> ground;
};

Result<PlanesFile> parse_planes_json(std::string_view text, const char* name = "planes.json");

}  // namespace petra::sim
