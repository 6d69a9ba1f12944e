// The scene's ground truth for scoring (truth.json, docs/scene.md): the ROI an
// operator would drag (or one inside the rock, `--roi-fill`), a click on the rock, the facets both
// cameras see (largest first, the c flat grind faces first of all), the ground plane and the sun.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "algo/core/image_view.hpp"
#include "sim/scene/disparity_truth.hpp"
#include "sim/scene/scene.hpp"
#include "sim/scene/scene_geometry.hpp"
#include "sim/scene/scene_rocks.hpp"

namespace petra::sim {

struct SceneTruth {
  Rect roi;            // original left image: rock, its shadow and a margin of ground
  Rect roi_rectified;  // bounding box of roi in the rectified left image
  // The operator's click (left original pixel): on the largest facet with
  // sunlit pixels inside roi, nearest their centroid (truth_pixels.hpp).
  std::optional<Eigen::Vector2i> click;
  int planes = 2;  // c: the designed flat faces
  std::vector<VisibleFacet> facets;
  double disparity_min = 0;  // valid truth disparities inside roi_rectified (px)
  double disparity_max = 0;
  // Realistic world only (measured on the rendered scene).
  std::vector<FacetFit> fits;     // per facet, when the faces are rough
  double relief_rms_roi_mm = -1;  // ground height RMS about its base plane in roi_rectified
  double vertical_rms_px = 0, vertical_max_px = 0;  // vertical disparity in roi_rectified
  // Multi-rock scenes only: every rock (rock 0 first, its facets, ROI and
  // click those above), each facet judged (scene_rocks.hpp).
  std::vector<RockTruth> rocks;
};

SceneTruth compute_truth(const Scene& scene, const RectifiedTruth& rect);

// truth.json text (contract fields plus optional extras).
Result<std::string> format_truth_json(const Scene& scene, const SceneTruth& truth);

}  // namespace petra::sim
