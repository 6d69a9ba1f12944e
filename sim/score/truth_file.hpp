// truth.json (written by `petra sim scene`, contract in docs/icd.md) read
// back for scoring. Required: roi, planes, facets (normal, centroid_mm,
// polygon_mm, visible_area_mm2), ground, sun_dir, seed. Optional extras:
// facets[].grind_face, facets[].flatness_rms_mm, roi_rectified, disparity_range,
// rocks (multi-rock scenes: each facet then needs grindable, reason,
// reachable, reach_reason).
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
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
  // Multi-rock scenes ("rocks"): the facet's judgement (docs/icd.md).
  bool grindable = false;
  std::string reason;  // grindable|too_small|too_rough|too_curved|faces_away|hidden
  bool reachable = false;
  std::string reach_reason;  // ok|beyond_reach|inside_reach|joint_limit|path_blocked
};

// One rock of a multi-rock scene (truth.json "rocks", rock 0 first).
struct TruthRock {
  int id = 0;
  Rect roi;
  std::optional<Eigen::Vector2i> click;
  double height_mm = 0;
  double size_mm = 0;
  std::vector<TruthFacet> facets;  // each with grindable, reason, reachable, reach_reason
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
  std::vector<TruthRock> rocks;  // empty unless a multi-rock scene
};

// `name` prefixes error messages. Checks: planes between 1 and the number of
// facets, polygons of at least 3 vertices, unit normals, ROI of positive size.
Result<TruthFile> parse_truth_json(std::string_view text, const char* name = "truth.json");

}  // namespace petra::sim
