// PROPOSE with the flight job (fsw/flight_pipeline_job: algo/propose's
// Proposer in the pipeline's place) in an executive in this process, on the
// simulated scene of seed 3 (rendered once per build tree, shared with
// test_flight_job_memory), in a region around its rock: the rock is listed
// first and offers a plane; SELECT_PROPOSAL then EVALUATE (the chain rebuilt
// in the proposer's place) downlinks that very plane (the same chain request:
// identical up to the PROPOSALS packet's f32); PROPOSAL_PLANES carries it among
// rank 1's planes; the picture follows. The whole
// 1024 x 768 view with neighbour rocks is algo/propose's own test
// (tests/sim/eval/test_propose_scene.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "fsw/pipeline_factory.hpp"
#include "sim/io/image_io.hpp"
#include "sim/score/truth_file.hpp"
#include "tests/fsw/executive_harness.hpp"
#include "tests/support/cached_dir.hpp"
#include "tests/support/text.hpp"

namespace petra {
namespace {

namespace fs = std::filesystem;
using cmd::FunctionCode;

TEST(FswPropose, TheRockIsProposedAndItsSelectionGivesTheSamePlane) {
  const fs::path scene =
      test::cached_petra_output("scene_seed3", PETRA_CLI_BIN, "sim scene --seed 3");
  ASSERT_FALSE(scene.empty()) << "petra sim scene --seed 3 failed";
  auto truth = sim::parse_truth_json(test::read_all(scene / "truth.json"));
  ASSERT_TRUE(truth.ok());
  test::ExecutiveHarness h(R"(,"calib":"calib.json")");
  const fs::path dir = h.dir();
  fs::copy_file(scene / "calib.json", dir / "calib.json");
  for (const char* side : {"left", "right"}) {
    auto img = io::read_gray_image((scene / (std::string(side) + ".png")).string());
    ASSERT_TRUE(img.ok());
    ASSERT_TRUE(
        io::write_pgm((dir / "camera" / (std::string(side) + "_000.pgm")).string(), img->view())
            .ok());
  }
  static hal::SystemClock clock;  // the job outlives the harness: static, as flight_pipeline() is
  h.pipeline = fsw::flight_pipeline(clock);
  h.budget = R"({"image_width":1024,"image_height":768})";  // the flight default
  ASSERT_TRUE(h.boot().ok());

  const Rect t = truth->roi;  // the region: the rock's box and 64 px around it
  cmd::ProposeArgs a;
  a.x_px = static_cast<std::uint16_t>(std::max(t.x - 64, 0));
  a.y_px = static_cast<std::uint16_t>(std::max(t.y - 64, 0));
  a.w_px = static_cast<std::uint16_t>(std::min(t.x + t.w + 64, 1024) - a.x_px);
  a.h_px = static_cast<std::uint16_t>(std::min(t.y + t.h + 64, 768) - a.y_px);
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
  const double cu = t.x + t.w / 2.0, cv = t.y + t.h / 2.0;  // the rock's box centre
  EXPECT_GE(cu, l.roi_px[0]);
  EXPECT_LT(cu, l.roi_px[0] + l.roi_px[2]);
  EXPECT_GE(cv, l.roi_px[1]);
  EXPECT_LT(cv, l.roi_px[1] + l.roi_px[3]);
  ASSERT_EQ(l.plane_offered[0], 1);
  // PROPOSAL_PLANES follows with every plane rank 1 carries; the one shown is among its offered.
  const auto carried = h.all<tlm::ProposalPlanes>();
  ASSERT_EQ(carried.size(), 1u);
  EXPECT_EQ(carried[0].proposal_id, l.proposal_id);
  EXPECT_EQ(carried[0].plane_count[0], l.plane_count[0]);
  int shown = 0;
  for (std::size_t j = 0; j < carried[0].plane_count[0]; ++j)
    shown += carried[0].offered[j] == 1 && carried[0].normal[3 * j] == l.normal[0] &&
                     carried[0].centroid_mm[3 * j + 2] == l.centroid_mm[2]
                 ? 1
                 : 0;
  EXPECT_EQ(shown, 1);

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
