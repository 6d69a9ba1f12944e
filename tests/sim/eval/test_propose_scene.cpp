// Rock proposals (algo/propose/proposer) on the shared multi-rock scene
// (tests/support/multirock_scene.hpp: seed 7, three rocks, the whole 1024 x
// 768 pair, no ROI or click given), scored as `petra score proposals` scores
// them against the scene's per-rock truth: every grindable, reachable
// designed flat face is offered, and 2 of the 3 grindable tangent facets
// (the third is one of issue 26's open misses); every offered plane lies on
// a target (precision 1), the best plane within 3 deg and 2 mm of its facet;
// sent back as SELECT_ROI, the chain gives the proposal's first plane again,
// bit for bit; the run takes no heap; a region of bare ground gives an empty
// list with its reason. Replaying the scene's true disparity (`petra propose
// --disparity`) offers the same faces, each exactly on its facet. The
// realistic multi-rock set's figures: docs/proposals.md.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "algo/camera/calib_json.hpp"
#include "algo/propose/proposer.hpp"
#include "sim/eval/proposals_json.hpp"
#include "sim/eval/propose_budget.hpp"
#include "sim/io/disparity_replay.hpp"
#include "sim/io/image_io.hpp"
#include "sim/score/proposal_score.hpp"
#include "sim/score/proposals_file.hpp"
#include "sim/score/truth_file.hpp"
#include "tests/support/heap_counter.hpp"
#include "tests/support/multirock_scene.hpp"

namespace petra {
namespace {

namespace fs = std::filesystem;

struct ProposeFixture {
  io::GrayImage left, right;
  sim::TruthFile truth;
  StereoRig rig;
};

std::string text_of(const fs::path& p) {
  auto t = io::read_text_file(p.string());
  EXPECT_TRUE(t.ok()) << p;
  return t.ok() ? *t : std::string("{}");
}

const ProposeFixture& propose_fixture() {
  static const ProposeFixture f = [] {
    ProposeFixture x;
    const fs::path& dir = test::multirock_scene_dir();
    EXPECT_FALSE(dir.empty()) << "the multi-rock scene could not be rendered";
    auto l = io::read_gray_image((dir / "left.png").string());
    auto r = io::read_gray_image((dir / "right.png").string());
    auto t = sim::parse_truth_json(text_of(dir / "truth.json"));
    auto c = parse_calib_json(text_of(dir / "calib.json"));
    EXPECT_TRUE(l.ok() && r.ok() && t.ok() && c.ok());
    if (l.ok() && r.ok() && t.ok() && c.ok()) {
      x.left = std::move(*l);
      x.right = std::move(*r);
      x.truth = std::move(*t);
      x.rig = *c;
    }
    return x;
  }();
  return f;
}

// The chain and its proposer in one arena (not moved after create: the
// proposer points to the pipeline).
struct ProposerRun {
  std::vector<std::byte> block;
  Arena arena;
  Result<Pipeline> pipeline = Error::make(Errc::not_ready, "not created");
  Result<Proposer> proposer = Error::make(Errc::not_ready, "not created");
};

void create(const ProposeFixture& f, ProposerRun& run) {
  auto budget = eval::ground_proposer_budget(f.rig, PipelineParams{});
  ASSERT_TRUE(budget.ok()) << budget.error().message;
  run.block.resize(Proposer::arena_bytes(*budget, PipelineParams{}));
  run.arena = Arena(run.block);
  run.pipeline = Pipeline::create(f.rig, budget->pipeline, PipelineParams{}, run.arena);
  ASSERT_TRUE(run.pipeline.ok()) << run.pipeline.error().message;
  run.proposer = Proposer::create(*run.pipeline, *budget, arm::rover_arm_geometry(),
                                  arm::default_joint_limits(), run.arena);
  ASSERT_TRUE(run.proposer.ok()) << run.proposer.error().message;
}

TEST(ProposeScene, EveryGrindableReachableFaceIsOfferedAndNothingElse) {
  const ProposeFixture& f = propose_fixture();
  ASSERT_FALSE(f.truth.rocks.empty());
  ProposerRun run;
  create(f, run);
  ASSERT_TRUE(run.proposer.ok());
  ProposalRequest all;
  all.max_proposals = kMaxProposals;
  Result<const ProposalList*> list = Error::make(Errc::not_ready, "not run");
  {
    const test::HeapScope heap;  // no heap after create
    list = run.proposer->run(f.left.view(), f.right.view(), all, arm::stow_pose(), {});
    EXPECT_EQ(heap.allocations(), 0u);
  }
  ASSERT_TRUE(list.ok()) << list.error().message;
  const ProposalList& l = **list;
  ASSERT_GE(l.count, 1) << l.empty_reason;
  const std::string json = eval::format_proposals_json(l);
  auto file = sim::parse_proposals_json(json);
  ASSERT_TRUE(file.ok()) << file.error().message;
  // Each offered plane says where the grinder goes and where the arm's reach left its disc.
  int planes = 0, offered = 0;
  for (int i = 0; i < l.count; ++i)
    for (int k = 0; k < l.items[i].plane_count; ++k) {
      ++planes;
      const GrindPlane& p = l.items[i].planes[k];
      if (p.verdict != PlaneVerdict::accepted || l.items[i].reach[k] != arm::ArmReason::ok)
        continue;
      ++offered;
      EXPECT_NE(p.footprint_reach, FootprintReach::not_asked) << "rank " << i + 1 << " plane " << k;
    }
  EXPECT_GE(offered, 1);
  std::size_t points = 0;
  for (std::size_t at = json.find("\"grind_point_mm\""); at != std::string::npos;
       at = json.find("\"grind_point_mm\"", at + 1))
    ++points;
  EXPECT_EQ(points, static_cast<std::size_t>(planes));
  auto score = sim::score_proposals(f.truth, *file, std::nullopt);
  ASSERT_TRUE(score.ok()) << score.error().message;
  EXPECT_GE(score->targets, 2);
  ASSERT_TRUE(score->recall && score->precision);
  EXPECT_DOUBLE_EQ(*score->precision, 1.0);
  // Every grindable, reachable designed flat face is offered, and 2 of the
  // rounded body's 3 grindable tangent facets (flat as rendered): the
  // proposal's further planes (algo/propose/further_planes), in the slots
  // the chain's unreachable faces held before (then 2 of the 5 targets). The
  // third tangent facet is one of issue 26's open misses.
  EXPECT_GE(score->targets_found, 4);
  for (const auto& [r, k] : score->missed)
    EXPECT_FALSE(
        f.truth.rocks[static_cast<std::size_t>(r)].facets[static_cast<std::size_t>(k)].grind_face)
        << "rock " << r << " facet " << k << ": a designed face missed";
  ASSERT_TRUE(score->best);
  EXPECT_TRUE(score->best->best.matches && score->best->best.target);
  EXPECT_LT(score->best->best.normal_error_deg, 3.0);
  EXPECT_LT(score->best->best.centroid_plane_mm, 2.0);
  EXPECT_TRUE(score->best->best.centroid_outside_mm <= 0.0)
      << "the best plane's centroid is off its facet";

  // Sent back as SELECT_ROI (its roi, click and planes_c) to the chain with
  // the same budget and the arm's reach: the chain's planes again, bit for bit; the proposal's
  // first plane is one the chain accepts (the rock's surplus planes the
  // proposal offers are listed there as surplus; its further planes,
  // algo/propose/further_planes, are not among them).
  const RockProposal& best = l.items[0];
  auto budget = eval::ground_proposer_budget(f.rig, PipelineParams{});
  ASSERT_TRUE(budget.ok());
  std::vector<std::byte> block(Pipeline::arena_bytes(budget->pipeline, PipelineParams{}));
  Arena arena(block);
  auto chain = Pipeline::create(f.rig, budget->pipeline, PipelineParams{}, arena);
  ASSERT_TRUE(chain.ok()) << chain.error().message;
  // As on board: the arm's reach from the pose the proposer was given.
  const arm::ArmGeometry geometry = arm::rover_arm_geometry();
  const arm::JointLimits limits = arm::default_joint_limits();
  const ArmReach reach(geometry, limits, arm::stow_pose(), arm::kDefaultStandoffMm);
  PipelineRequest select;
  select.reach = &reach;
  select.roi = best.rock.roi;
  select.has_click = true;
  select.click_u = best.rock.click_u;
  select.click_v = best.rock.click_v;
  select.planes = best.planes_c;
  auto again = chain->run(f.left.view(), f.right.view(), select, {});
  ASSERT_TRUE(again.ok()) << again.error().message;
  const GrindResult& g = again->result.planes;
  auto chain_verdict = [&](const GrindPlane& p) {
    for (int k = 0; k < g.count; ++k)
      if (g.planes[k].normal == p.normal && g.planes[k].centroid_mm == p.centroid_mm)
        return g.planes[k].verdict;
    return PlaneVerdict::no_support;
  };
  ASSERT_GE(best.plane_count, 1);
  EXPECT_EQ(chain_verdict(best.planes[0]), PlaneVerdict::accepted);

  // Last (the list is the proposer's, rewritten by each run): a region of
  // bare ground gives an empty list with its reason.
  ProposalRequest bare;
  bare.region = {0, 0, 300, 250};
  auto none = run.proposer->run(f.left.view(), f.right.view(), bare, arm::stow_pose(), {});
  ASSERT_TRUE(none.ok()) << none.error().message;
  EXPECT_EQ((*none)->count, 0);
  EXPECT_STREQ((*none)->empty_reason, "no rock stands out of the ground");
}

// The candidates' chain runs replay a given map instead of matching: on the
// exact map the back half puts every offered plane on its facet (the matched
// run's are up to about a degree off), so a miss left then is the back
// half's, not the matcher's. A map that does not cover a candidate's ROI is
// that candidate's refusal, with the reason.
TEST(ProposeScene, ReplayedTruthMapPutsEveryOfferedPlaneOnItsFacet) {
  const ProposeFixture& f = propose_fixture();
  ASSERT_FALSE(f.truth.rocks.empty());
  auto q4 = io::read_disparity_q4((test::multirock_scene_dir() / "disparity_truth.pfm").string(),
                                  f.left.width, f.left.height);
  ASSERT_TRUE(q4.ok()) << q4.error().message;
  const ConstDisparityMap whole(
      ImageView<const std::int16_t>(q4->data(), f.left.width, f.left.height),
      Rect{0, 0, f.left.width, f.left.height});
  ProposerRun run;
  create(f, run);
  ASSERT_TRUE(run.proposer.ok());
  ProposalRequest all;
  all.max_proposals = kMaxProposals;
  auto list = run.proposer->run(f.left.view(), f.right.view(), all, arm::stow_pose(), {}, &whole);
  ASSERT_TRUE(list.ok()) << list.error().message;
  auto file = sim::parse_proposals_json(eval::format_proposals_json(**list));
  ASSERT_TRUE(file.ok()) << file.error().message;
  auto score = sim::score_proposals(f.truth, *file, std::nullopt);
  ASSERT_TRUE(score.ok()) << score.error().message;
  EXPECT_GE(score->targets_found, 4);
  int offered = 0;
  for (const sim::ScoredPlane& p : score->planes) {
    if (!p.offered) continue;
    ++offered;
    EXPECT_TRUE(p.best.matches && p.best.target) << "rank " << p.rank << " plane " << p.index;
    EXPECT_LT(p.best.normal_error_deg, 0.1) << "rank " << p.rank << " plane " << p.index;
    EXPECT_LT(p.best.centroid_plane_mm, 0.05) << "rank " << p.rank << " plane " << p.index;
  }
  EXPECT_GE(offered, 4);

  // A map of the top-left quarter only: no candidate's ROI lies inside it.
  const ConstDisparityMap quarter(
      ImageView<const std::int16_t>(q4->data(), f.left.width / 2, f.left.height / 2, f.left.width),
      Rect{0, 0, f.left.width / 2, f.left.height / 2});
  auto refused =
      run.proposer->run(f.left.view(), f.right.view(), all, arm::stow_pose(), {}, &quarter);
  ASSERT_TRUE(refused.ok()) << refused.error().message;
  ASSERT_GE((*refused)->candidates, 1);
  const RockProposal& first = (*refused)->items[0];
  EXPECT_EQ(first.note, ProposalNote::chain_refused);
  EXPECT_NE(std::string(first.chain_error.message).find("does not cover the ROI"),
            std::string::npos)
      << first.chain_error.message;
}

}  // namespace
}  // namespace petra
