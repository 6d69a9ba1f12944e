// PROPOSE with the flight job (fsw/flight_pipeline_job: algo/propose's
// Proposer in the pipeline's place) in an executive in this process, on a
// realistic scene with two touching neighbour rocks (realistic set entry 25,
// as tests/sim/eval/test_propose_scene.cpp, fewer edge samples): the rock
// under the truth click is listed first and offers a plane; SELECT_PROPOSAL
// then EVALUATE (the chain rebuilt in the proposer's place) downlinks that
// very plane (the same chain request: identical up to the PROPOSALS packet's
// f32); the picture follows.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "fsw/pipeline_factory.hpp"
#include "sim/scene/scene_set.hpp"
#include "tests/fsw/executive_harness.hpp"
#include "tests/support/rendered_scene.hpp"

namespace petra {
namespace {

using cmd::FunctionCode;

TEST(FswPropose, TheTargetRockIsProposedAndItsSelectionGivesTheSamePlane) {
  test::ExecutiveHarness h(R"(,"calib":"scene/calib.json")");
  sim::SceneOptions o = sim::real_scene_set()[25];
  o.edge_supersampling = 2;
  const test::RenderedScene scene = test::render_for_test(o);
  ASSERT_TRUE(scene.products.truth.click.has_value());
  const std::filesystem::path dir = h.dir();
  ASSERT_TRUE(sim::write_scene(scene.products, (dir / "scene").string()).ok());
  for (const char* side : {"left", "right"})
    std::filesystem::copy_file(dir / "scene" / (std::string(side) + ".pgm"),
                               dir / "camera" / (std::string(side) + "_000.pgm"),
                               std::filesystem::copy_options::overwrite_existing);
  static hal::SystemClock clock;  // the job outlives the harness: static, as flight_pipeline() is
  h.pipeline = fsw::flight_pipeline(clock);
  h.budget = R"({"image_width":1024,"image_height":768})";  // the flight default
  ASSERT_TRUE(h.boot().ok());

  cmd::ProposeArgs a;
  a.acquire = 1;
  a.count = 4;
  a.weight_grindable = 1.0f;
  a.weight_reach = 1.0f;
  a.weight_certainty = 0.5f;
  a.weight_size = 0.25f;
  const auto propose = h.make(FunctionCode::PROPOSE, a);
  h.send(propose);
  auto done = [&](std::uint32_t c) {
    return h.has_ack(c, AckStage::COMPLETED) || h.has_ack(c, AckStage::FAILED);
  };
  ASSERT_TRUE(h.cycle_until([&] { return done(propose.counter); }, 60000));
  ASSERT_TRUE(h.has_ack(propose.counter, AckStage::COMPLETED));
  const auto lists = h.all<tlm::Proposals>();
  ASSERT_EQ(lists.size(), 1u);
  const tlm::Proposals& l = lists[0];
  ASSERT_GE(l.count, 1);
  EXPECT_EQ(l.status, 0) << "empty reason " << int{l.empty_reason};
  const double cu = scene.products.truth.click->x(), cv = scene.products.truth.click->y();
  EXPECT_GE(cu, l.roi_px[0]);
  EXPECT_LT(cu, l.roi_px[0] + l.roi_px[2]);
  EXPECT_GE(cv, l.roi_px[1]);
  EXPECT_LT(cv, l.roi_px[1] + l.roi_px[3]);
  ASSERT_EQ(l.plane_offered[0], 1);

  cmd::SelectProposalArgs pick;
  pick.proposal_id = l.proposal_id;
  pick.rank = 1;
  const auto sel = h.make(FunctionCode::SELECT_PROPOSAL, pick);
  const auto eval = h.make(FunctionCode::EVALUATE, cmd::EvaluateArgs{0});
  h.send(sel);
  h.send(eval);
  ASSERT_TRUE(h.cycle_until([&] { return done(eval.counter); }, 60000));
  ASSERT_TRUE(h.has_ack(sel.counter, AckStage::COMPLETED));
  ASSERT_TRUE(h.has_ack(eval.counter, AckStage::COMPLETED));
  const auto planes = h.all<tlm::GrindPlane>();
  int same = 0;
  for (const tlm::GrindPlane& p : planes) {
    bool equal = true;
    for (std::size_t c = 0; c < 3; ++c)
      equal = equal && static_cast<float>(p.normal[c]) == l.normal[c] &&
              static_cast<float>(p.centroid_mm[c]) == l.centroid_mm[c];
    same += equal ? 1 : 0;
  }
  EXPECT_EQ(same, 1) << planes.size() << " planes, none is the proposal's offered plane";
  // The picture came with the list.
  ASSERT_TRUE(h.cycle_until([&] {
    for (const auto& c : h.all<tlm::Product>())
      if (c.product == 5 && c.id == l.proposal_id && c.chunk + 1 == c.chunks) return true;
    return false;
  }));
}

}  // namespace
}  // namespace petra
