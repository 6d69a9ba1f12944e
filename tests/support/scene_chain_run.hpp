// The chain on a rendered scene (rendered_scene.hpp) with the truth's ROI and
// c (and its click, when asked and present), scored against the truth: what
// the tests that run Pipeline::run on one simulated scene share.
#pragma once

#include <gtest/gtest.h>

#include <vector>

#include "algo/chain/pipeline.hpp"
#include "sim/eval/planes_json.hpp"
#include "sim/score/plane_score.hpp"
#include "sim/score/planes_file.hpp"
#include "tests/support/eval_budget.hpp"
#include "tests/support/rendered_scene.hpp"

namespace petra::test {

struct SceneChainRun {
  Result<PipelineOutput> out = Error::make(Errc::not_ready, "not run");
  sim::PlaneScore score;
};

// `rig`: the calibration the chain is given (the scene's own, or one made
// wrong on purpose); max_roi: the budget's ROI side.
inline SceneChainRun run_chain_on_scene(const RenderedScene& f, const StereoRig& rig,
                                        const PipelineParams& params, int max_roi,
                                        bool with_click) {
  const PipelineBudget b = eval_budget(rig.left.width, rig.left.height, max_roi, params);
  std::vector<std::byte> block(Pipeline::arena_bytes(b, params));
  Arena arena(block);
  auto pipeline = Pipeline::create(rig, b, params, arena);
  EXPECT_TRUE(pipeline.ok()) << pipeline.error().message;
  PipelineRequest q;
  q.roi = f.truth.roi;
  q.planes = f.truth.planes;
  q.has_click = with_click && f.products.truth.click.has_value();
  if (q.has_click) {
    q.click_u = f.products.truth.click->x();
    q.click_v = f.products.truth.click->y();
  }
  SceneChainRun o;
  o.out = pipeline->run(f.products.left.image.view(), f.products.right.image.view(), q, {});
  if (o.out.ok()) {
    auto planes = sim::parse_planes_json(eval::format_planes_json(o.out->result));
    EXPECT_TRUE(planes.ok());
    if (planes.ok()) o.score = sim::score_planes(f.truth, *planes);
  }
  return o;
}

// Every designed face found within the realistic set's targets (3 deg, 2 mm,
// on its facet) and the plane count right.
inline void expect_realistic_targets(const sim::PlaneScore& score) {
  EXPECT_TRUE(score.count_agrees) << score.output_planes << " for " << score.truth_planes;
  for (const sim::FacetScore& s : score.facets) {
    ASSERT_GE(s.plane, 0) << "facet " << s.facet << " unmatched";
    EXPECT_LE(s.normal_error_deg, 3.0) << "facet " << s.facet;
    EXPECT_LE(s.centroid_plane_distance_mm, 2.0) << "facet " << s.facet;
    EXPECT_TRUE(s.centroid_on_facet) << "facet " << s.facet;
  }
}

}  // namespace petra::test
