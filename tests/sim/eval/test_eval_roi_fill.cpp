// A rock that fills the ROI (realistic set entry 31: two faces, no ground in
// the ROI, `--roi-fill`): the ground fit alone accepts a plane laid across the
// two faces' outer parts, with the ridge above it, as "ground". Its points
// lean away from that plane (algo/surface/ground_normals), so the chain
// grows the rock from the operator's click instead and finds both faces.
// Rendered with fewer edge samples than the set so the check build renders it
// in seconds; the trap is there as in the set's render (docs/reconstruction.md).
#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "algo/camera/calib_json.hpp"
#include "algo/chain/pipeline.hpp"
#include "sim/eval/planes_json.hpp"
#include "sim/scene/scene_render.hpp"
#include "sim/scene/scene_set.hpp"
#include "sim/score/plane_score.hpp"
#include "sim/score/planes_file.hpp"
#include "sim/score/truth_file.hpp"

namespace petra {
namespace {

struct Fixture {
  sim::SceneProducts scene;
  sim::TruthFile truth;
  StereoRig rig;
};

const Fixture& fixture() {
  static const Fixture f = [] {
    Fixture x;
    sim::SceneOptions o = sim::real_scene_set()[31];
    o.edge_supersampling = 2;
    auto p = sim::render_scene(o);
    EXPECT_TRUE(p.ok()) << p.error().message;
    x.scene = std::move(*p);
    x.truth = *sim::parse_truth_json(x.scene.truth_json);
    x.rig = *parse_calib_json(x.scene.calib_json);
    return x;
  }();
  return f;
}

struct Outcome {
  Result<PipelineOutput> out = Error::make(Errc::not_ready, "not run");
  sim::PlaneScore score;
};

// The chain on the fixture with the truth's ROI, c and click.
Outcome evaluate(const Fixture& f, const PipelineParams& params) {
  PipelineBudget b;
  b.image_width = f.rig.left.width;
  b.image_height = f.rig.left.height;
  b.max_roi_width = 320;
  b.max_roi_height = 320;
  b.max_disparities = 128;
  std::vector<std::byte> block(Pipeline::arena_bytes(b, params));
  Arena arena(block);
  auto pipeline = Pipeline::create(f.rig, b, params, arena);
  EXPECT_TRUE(pipeline.ok()) << pipeline.error().message;
  PipelineRequest q;
  q.roi = f.truth.roi;
  q.planes = f.truth.planes;
  q.has_click = f.scene.truth.click.has_value();
  if (q.has_click) {
    q.click_u = f.scene.truth.click->x();
    q.click_v = f.scene.truth.click->y();
  }
  Outcome o;
  o.out = pipeline->run(f.scene.left.image.view(), f.scene.right.image.view(), q, {});
  if (o.out.ok()) {
    auto planes = sim::parse_planes_json(eval::format_planes_json(o.out->result));
    EXPECT_TRUE(planes.ok());
    if (planes.ok()) o.score = sim::score_planes(f.truth, *planes);
  }
  return o;
}

TEST(EvalRoiFill, TwoFacesAreNotTakenForGround) {
  const Fixture& f = fixture();
  ASSERT_TRUE(f.scene.truth.click.has_value());
  // Without the normals' check the two faces pass as ground (the trap).
  PipelineParams off;
  off.reconstruction.ground_normals.min_share = 0.0;
  const Outcome trap = evaluate(f, off);
  ASSERT_TRUE(trap.out.ok()) << trap.out.error().message;
  EXPECT_EQ(trap.out->result.segmentation, SegmentMethod::ground_plane);
  // With it (the flight default) the rock is grown from the click.
  const Outcome o = evaluate(f, {});
  ASSERT_TRUE(o.out.ok()) << o.out.error().message;
  EXPECT_EQ(o.out->result.segmentation, SegmentMethod::click_region);
  EXPECT_TRUE(o.score.count_agrees) << o.score.output_planes << " for " << o.score.truth_planes;
  for (const sim::FacetScore& s : o.score.facets) {
    ASSERT_GE(s.plane, 0) << "facet " << s.facet << " unmatched";
    EXPECT_LE(s.normal_error_deg, 3.0) << "facet " << s.facet;
    EXPECT_LE(s.centroid_plane_distance_mm, 2.0) << "facet " << s.facet;
    EXPECT_TRUE(s.centroid_on_facet) << "facet " << s.facet;
  }
}

}  // namespace
}  // namespace petra
