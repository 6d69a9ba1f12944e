// The proposer's pieces that need no images: the request refused by field
// name, the score's terms and total, the note names telemetry carries, and
// create over the caller's pipeline, the planes left to a neighbour's run.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "algo/propose/proposer.hpp"
#include "tests/support/test_rig.hpp"

namespace petra {
namespace {

std::string refusal(const ProposalRequest& r) {
  const Status s = validate(r, 1024, 768);
  return s.ok() ? std::string() : std::string(s.error().message);
}

TEST(Proposer, RequestRefusedByFieldName) {
  EXPECT_EQ(refusal(ProposalRequest{}), "");
  ProposalRequest r;
  r.region = {1000, 10, 100, 100};
  EXPECT_EQ(refusal(r).rfind("region:", 0), 0u) << refusal(r);
  r = {};
  r.max_proposals = 0;
  EXPECT_EQ(refusal(r).rfind("max_proposals:", 0), 0u);
  r.max_proposals = kMaxProposals + 1;
  EXPECT_EQ(refusal(r).rfind("max_proposals:", 0), 0u);
  r = {};
  r.weights.reach = 1.5;
  EXPECT_EQ(refusal(r).rfind("weights.reach:", 0), 0u);
  r.weights.reach = std::nan("");
  EXPECT_EQ(refusal(r).rfind("weights.reach:", 0), 0u);
  r = {};
  r.weights = {0, 0, 0, 0};
  EXPECT_EQ(refusal(r).rfind("weights:", 0), 0u);
}

TEST(Proposer, ScoreTermsAndWeightedTotal) {
  const GrindParams grind;
  GrindPlane p;
  p.verdict = PlaneVerdict::accepted;
  p.footprint_rms_mm = 0.5 * grind.max_footprint_rms_mm;  // grindable 0.75
  p.normal_sigma_deg = 0.5 * grind.max_normal_sigma_deg;  // certainty 1 - (0.25 + 0)
  p.offset_sigma_mm = 0;
  const double disc = M_PI / 4 * 20.0 * 20.0;
  p.area_mm2 = 2 * disc;  // size 0.5
  const ProposalWeights w{1.0, 1.0, 0.5, 0.25};
  const ProposalScore s = score_plane(&p, true, 20.0, grind, w);
  EXPECT_DOUBLE_EQ(s.grindable, 0.75);
  EXPECT_DOUBLE_EQ(s.reach, 1.0);
  EXPECT_DOUBLE_EQ(s.certainty, 0.75);
  EXPECT_DOUBLE_EQ(s.size, 0.5);
  EXPECT_DOUBLE_EQ(s.total, (0.75 + 1.0 + 0.5 * 0.75 + 0.25 * 0.5) / 2.75);
  // Unreachable and not grindable: those terms drop to 0.
  p.verdict = PlaneVerdict::too_rough;
  const ProposalScore u = score_plane(&p, false, 20.0, grind, w);
  EXPECT_EQ(u.grindable, 0.0);
  EXPECT_EQ(u.reach, 0.0);
  EXPECT_LT(u.total, s.total);
  EXPECT_EQ(score_plane(nullptr, false, 20.0, grind, w).total, 0.0);
}

TEST(Proposer, NoteNamesAreStableKeys) {
  EXPECT_STREQ(proposal_note_name(ProposalNote::ok), "ok");
  EXPECT_STREQ(proposal_note_name(ProposalNote::no_grindable_plane), "no_grindable_plane");
  EXPECT_STREQ(proposal_note_name(ProposalNote::chain_refused), "chain_refused");
  EXPECT_STREQ(proposal_note_name(ProposalNote::unreachable), "unreachable");
}

// The proposer builds nothing: it runs the caller's pipeline (the same
// object, its tables), takes no byte at create, and refuses a pipeline built
// for another budget or an arena without room for its detection.
TEST(Proposer, CreateUsesTheCallersPipelineAndBuildsNothing) {
  const StereoRig rig = test::bumblebee_rig(3);
  const ProposerBudget budget;  // the chain's 1024 x 768, the rig's
  std::vector<std::byte> block(Proposer::arena_bytes(budget, PipelineParams{}));
  Arena arena(block);
  auto pipeline = Pipeline::create(rig, budget.pipeline, PipelineParams{}, arena);
  ASSERT_TRUE(pipeline.ok()) << pipeline.error().message;
  const std::size_t tables_end = arena.mark();
  const auto create = [&](const ProposerBudget& b) {
    return Proposer::create(*pipeline, b, arm::rover_arm_geometry(), arm::default_joint_limits(),
                            arena);
  };
  auto proposer = create(budget);
  ASSERT_TRUE(proposer.ok()) << proposer.error().message;
  EXPECT_EQ(arena.mark(), tables_end);
  EXPECT_EQ(&proposer->pipeline(), &*pipeline);

  ProposerBudget other = budget;
  other.pipeline.max_roi_width -= 16;
  EXPECT_EQ(create(other).code(), Errc::invalid_argument);

  ASSERT_GT(arena.remaining(), Proposer::detection_bytes(budget));
  ASSERT_TRUE(arena
                  .allocate<std::byte>(arena.remaining() - Proposer::detection_bytes(budget) + 1,
                                       "test: the space taken")
                  .ok());
  EXPECT_EQ(create(budget).code(), Errc::capacity_exceeded);
}

// A chain run's planes on a 4 x 1 rock map (factor 4): plane 0 on rock 1
// (the clicked one), plane 1 mostly on rock 0 (a neighbour in the ROI),
// plane 2 on ground the map calls no rock, plane 3 half and half.
TEST(Proposer, PlanesOnAnotherRockAreTheNeighbours) {
  const std::uint8_t map[4] = {0, 1, kNoRock, kOtherRock};
  std::vector<PixelPos> px;
  std::vector<std::uint8_t> cls;
  auto add = [&](int plane, int grid_x, int n) {
    for (int i = 0; i < n; ++i) {
      px.push_back({static_cast<std::int16_t>(grid_x * 4 + i % 4), 2});
      cls.push_back(static_cast<std::uint8_t>(kVertexPlane0 + plane));
    }
  };
  add(0, 1, 10);
  add(1, 0, 7), add(1, 1, 3);
  add(2, 2, 5);
  add(3, 1, 4), add(3, 3, 4);
  px.push_back({0, 2}), cls.push_back(kVertexRock);  // not on a plane: no vote
  ReconstructionOutput r;
  r.pixels = px;
  r.vertex_class = cls;
  bool other[kMaxClasses] = {};
  planes_on_other_rocks(r, RockOnMap{map, 4, 4, 1}, other);
  EXPECT_FALSE(other[0]);
  EXPECT_TRUE(other[1]);
  EXPECT_FALSE(other[2]);  // no rock's: kept (the rock's low flank is ground-labelled)
  EXPECT_FALSE(other[3]);  // a tie stays with the clicked rock
  planes_on_other_rocks(r, RockOnMap{map, 4, 4, 0}, other);  // the neighbour's own run
  EXPECT_TRUE(other[0]);
  EXPECT_FALSE(other[1]);
}

}  // namespace
}  // namespace petra
