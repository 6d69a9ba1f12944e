// A rock that fills the ROI (realistic set entry 31: two faces, no ground in
// the ROI, `--roi-fill`): the ground fit alone accepts a plane laid across the
// two faces' outer parts, with the ridge above it, as "ground". Its points
// lean away from that plane (algo/surface/ground_normals), so the chain
// grows the rock from the operator's click instead and finds both faces.
// Rendered with fewer edge samples than the set and only where the chain
// reads (the ROI and 48 px around it, in the right view shifted by the
// truth's disparities), so the check build renders it in a fraction of the
// whole pair's time; the trap is there as in the set's render
// (docs/reconstruction.md) on the DP's map with raw gray levels.
#include <gtest/gtest.h>

#include "algo/chain/pipeline.hpp"
#include "sim/scene/scene_set.hpp"
#include "tests/support/rendered_scene.hpp"
#include "tests/support/scene_chain_run.hpp"

namespace petra {
namespace {

using RoiFillScene = test::RenderedScene;

const RoiFillScene& roi_fill_scene() {
  static const RoiFillScene f = [] {
    sim::SceneOptions o = sim::real_scene_set()[31];
    o.edge_supersampling = 2;
    return test::render_for_test(o, 48);
  }();
  return f;
}

// The chain on the fixture with the truth's ROI, c and click.
test::SceneChainRun evaluate(const RoiFillScene& f, const PipelineParams& params) {
  return test::run_chain_on_scene(f, f.rig, params, 320, true);
}

TEST(EvalRoiFill, TwoFacesAreNotTakenForGround) {
  const RoiFillScene& f = roi_fill_scene();
  ASSERT_TRUE(f.products.truth.click.has_value());
  // The trap springs on the map the DP makes with raw gray levels (the
  // right camera's gain uncorrected, the flight default before the gray-level
  // map): without the normals' check the two faces pass as ground.
  PipelineParams raw;
  raw.match.normalise_gray = false;
  PipelineParams off = raw;
  off.reconstruction.ground_normals.min_share = 0.0;
  const test::SceneChainRun trap = evaluate(f, off);
  ASSERT_TRUE(trap.out.ok()) << trap.out.error().message;
  EXPECT_EQ(trap.out->result.segmentation, SegmentMethod::ground_plane);
  // With the check the rock is grown from the click, on that map ...
  const test::SceneChainRun checked = evaluate(f, raw);
  ASSERT_TRUE(checked.out.ok()) << checked.out.error().message;
  EXPECT_EQ(checked.out->result.segmentation, SegmentMethod::click_region);
  test::expect_realistic_targets(checked.score);
  // ... and with the flight default.
  const test::SceneChainRun o = evaluate(f, {});
  ASSERT_TRUE(o.out.ok()) << o.out.error().message;
  EXPECT_EQ(o.out->result.segmentation, SegmentMethod::click_region);
  test::expect_realistic_targets(o.score);
}

}  // namespace
}  // namespace petra
