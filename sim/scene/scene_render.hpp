// Everything `petra sim scene` produces for one scene, in memory, and the
// files it writes (names and meaning in docs/scene.md):
//   left.pgm/.png, right.pgm/.png  the stereo pair (8-bit, original geometry)
//   calib.json                     the rig (contract)
//   truth.json                     ROI, facets, ground, sun, seed (contract)
//   disparity_truth.pfm            rectified left view, +inf where invalid
//   shadow_truth.pgm               original left image, 255 = shadow
//   shadow_truth_right.pgm         original right image, 255 = shadow
//   shadow_truth_rectified.pgm     rectified left view, 255 = shadow
#pragma once

#include <string>

#include "sim/scene/disparity_truth.hpp"
#include "sim/scene/render_view.hpp"
#include "sim/scene/scene.hpp"
#include "sim/scene/scene_truth.hpp"

namespace petra::sim {

struct SceneProducts {
  Scene scene;
  RenderedView left;
  RenderedView right;
  RectifiedTruth rectified;
  SceneTruth truth;
  std::string calib_json;
  std::string truth_json;
};

Result<SceneProducts> render_scene(const SceneOptions& options);

// As render_scene, but each view only where a chain run on the truth's ROI
// reads it, the rest 0: the left view in the ROI and `margin` px around it,
// the right view in the same rows and the columns the ROI's truth disparities
// (and the margin) reach. A pixel's value does not depend on the window
// rendered (render_view), so such a test gets the same pixels there in a
// fraction of the time.
Result<SceneProducts> render_scene_roi_window(const SceneOptions& options, int margin);

// Creates `dir` when missing; fails when it cannot (checked before rendering).
Status prepare_output_dir(const std::string& dir);
// Creates `dir` when missing and writes every file; errors name the file.
Status write_scene(const SceneProducts& products, const std::string& dir);

}  // namespace petra::sim
