// truth.json (written by `petra sim scene`, contract in docs/icd.md) read
// back for scoring. Required: roi, planes, facets (normal, centroid_mm,
// polygon_mm, visible_area_mm2), ground, sun_dir, seed. Optional extras:
// facets[].grind_face, facets[].flatness_rms_mm, roi_rectified, disparity_range.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string_view>
#include <vector>

#include "algo/core/image_view.hpp"
#include "algo/core/result.hpp"
#include "sim/scene/polygon3.hpp"

namespace petra::sim {

struct TruthFacet {
  Eigen::Vector3d normal;  // unit, out of the rock
  Eigen::Vector3d centroid_mm;
  Polygon3 polygon_mm;
  double visible_area_mm2 = 0;
  bool grind_face = false;
  std::optional<double> flatness_rms_mm;  // rough faces: RMS about the fitted plane
};

struct TruthFile {
  Rect roi;  // original left image
  int planes = 0;
  std::vector<TruthFacet> facets;
  Eigen::Vector3d ground_normal = Eigen::Vector3d::UnitZ();
  double ground_d_mm = 0;  // ground: normal.X + d = 0
  Eigen::Vector3d sun_dir = Eigen::Vector3d::UnitZ();
  long long seed = 0;
  std::optional<Rect> roi_rectified;
};

// `name` prefixes error messages. Checks: planes between 1 and the number of
// facets, polygons of at least 3 vertices, unit normals, ROI of positive size.
Result<TruthFile> parse_truth_json(std::string_view text, const char* name = "truth.json");

}  // namespace petra::sim
