// The footprint disc the arm reaches, judged on the plane ARM_GOTO plans on
// (algo/chain/grind_plane_reach): on scene_05 of the multi-rock set (`petra
// sim set --multi`, seed 3005: the realistic world, four rocks) the photometric
// refinement turned two faces of rock 3 off the discs the grind step had
// found in the arm's reach (both listed `most_level`, then `joint_limit`, one
// of them a target the truth reaches). Now every plane a proposal lists as
// reached at its disc is reached along its reported normal, and that target
// (rock 3 facet 1) is offered.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "algo/camera/calib_json.hpp"
#include "algo/propose/arm_reach.hpp"
#include "algo/propose/proposer.hpp"
#include "sim/eval/proposals_json.hpp"
#include "sim/eval/propose_budget.hpp"
#include "sim/io/image_io.hpp"
#include "sim/scene/scene_render.hpp"
#include "sim/scene/scene_set.hpp"
#include "sim/score/proposal_score.hpp"
#include "sim/score/proposals_file.hpp"
#include "sim/score/truth_file.hpp"
#include "tests/support/cached_dir.hpp"

namespace petra {
namespace {

namespace fs = std::filesystem;

const fs::path& multi_set_scene_05() {
  static const fs::path dir =
      test::cached_dir("multi_set_scene_05", "sim set --multi, scene_05", test::this_executable(),
                       [](const fs::path& out) {
                         auto p = sim::render_scene(sim::multi_rock_scene_set()[5]);
                         return p && sim::write_scene(*p, out.string()).ok();
                       });
  return dir;
}

std::string scene_05_text(const char* name) {
  auto t = io::read_text_file((multi_set_scene_05() / name).string());
  EXPECT_TRUE(t.ok()) << name;
  return t.ok() ? *t : std::string("{}");
}

TEST(ProposeRefinedReach, EveryDiscListedAsReachedIsReachedAlongTheReportedNormal) {
  const fs::path& dir = multi_set_scene_05();
  ASSERT_FALSE(dir.empty()) << "scene_05 of the multi-rock set could not be rendered";
  auto left = io::read_gray_image((dir / "left.png").string());
  auto right = io::read_gray_image((dir / "right.png").string());
  auto truth = sim::parse_truth_json(scene_05_text("truth.json"));
  auto rig = parse_calib_json(scene_05_text("calib.json"));
  ASSERT_TRUE(left.ok() && right.ok() && truth.ok() && rig.ok());

  auto budget = eval::ground_proposer_budget(*rig, PipelineParams{});
  ASSERT_TRUE(budget.ok()) << budget.error().message;
  std::vector<std::byte> block(Proposer::arena_bytes(*budget, PipelineParams{}));
  Arena arena(block);
  auto pipeline = Pipeline::create(*rig, budget->pipeline, PipelineParams{}, arena);
  ASSERT_TRUE(pipeline.ok()) << pipeline.error().message;
  const arm::ArmGeometry geometry = arm::rover_arm_geometry();
  const arm::JointLimits limits = arm::default_joint_limits();
  auto proposer = Proposer::create(*pipeline, *budget, geometry, limits, arena);
  ASSERT_TRUE(proposer.ok()) << proposer.error().message;
  ProposalRequest all;
  all.max_proposals = kMaxProposals;
  auto list = proposer->run(left->view(), right->view(), all, arm::stow_pose(), {});
  ASSERT_TRUE(list.ok()) << list.error().message;

  const ArmReach reach(geometry, limits, arm::stow_pose(), arm::kDefaultStandoffMm);
  int reached_discs = 0;
  for (int i = 0; i < (*list)->count; ++i)
    for (int k = 0; k < (*list)->items[i].plane_count; ++k) {
      const GrindPlane& p = (*list)->items[i].planes[k];
      if (p.footprint_reach != FootprintReach::most_level &&
          p.footprint_reach != FootprintReach::moved)
        continue;
      ++reached_discs;
      EXPECT_EQ(reach.why(p.centroid_mm, p.normal), arm::ArmReason::ok)
          << "rank " << i + 1 << " plane " << k << ": listed as reached at its disc";
    }
  EXPECT_GE(reached_discs, 3);

  auto file = sim::parse_proposals_json(eval::format_proposals_json(**list));
  ASSERT_TRUE(file.ok()) << file.error().message;
  auto score = sim::score_proposals(*truth, *file, std::nullopt);
  ASSERT_TRUE(score.ok()) << score.error().message;
  for (const auto& [r, k] : score->missed)
    EXPECT_FALSE(r == 3 && k == 1) << "rock 3 facet 1 (a target the arm reaches) missed";
  ASSERT_TRUE(score->precision);
  EXPECT_DOUBLE_EQ(*score->precision, 1.0);
}

}  // namespace
}  // namespace petra
