// The proposer's pieces that need no images: the request refused by field
// name, the score's terms and total, the note names telemetry carries, and
// create over the caller's pipeline.
#include <gtest/gtest.h>

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

}  // namespace
}  // namespace petra
