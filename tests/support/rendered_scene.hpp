// A simulated scene rendered once in the test process, with its truth and rig
// parsed: the fixture of the tests that run the chain on a scene.
#pragma once

#include <gtest/gtest.h>

#include <utility>

#include "algo/camera/calib_json.hpp"
#include "sim/scene/scene_render.hpp"
#include "sim/score/truth_file.hpp"

namespace petra::test {

struct RenderedScene {
  sim::SceneProducts products;
  sim::TruthFile truth;
  StereoRig rig;
};

// margin >= 0: each view only where a chain run on the truth's ROI reads it
// (sim::render_scene_roi_window), for a test that runs only that.
inline RenderedScene render_for_test(const sim::SceneOptions& options, int margin = -1) {
  RenderedScene x;
  auto p = margin < 0 ? sim::render_scene(options) : sim::render_scene_roi_window(options, margin);
  EXPECT_TRUE(p.ok()) << p.error().message;
  if (!p.ok()) return x;
  x.products = std::move(*p);
  x.truth = *sim::parse_truth_json(x.products.truth_json);
  x.rig = *parse_calib_json(x.products.calib_json);
  return x;
}

}  // namespace petra::test
