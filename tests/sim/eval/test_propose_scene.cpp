// Rock proposals (algo/propose/proposer) on a realistic scene with two
// touching neighbour rocks (realistic set entry 25: `petra sim scene --real
// --set-index 25`, docs/scene.md "Neighbours"), the whole 1024 x 768 pair, no
// ROI or click given: the target rock is detected and offered, and its
// offered plane lies within 3 deg and 2 mm of one of its truth facets.
// Rendered with fewer edge samples than the set so the check build renders it
// in seconds (as test_eval_roi_fill).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "algo/propose/proposer.hpp"
#include "sim/eval/proposals_json.hpp"
#include "sim/eval/propose_budget.hpp"
#include "sim/scene/scene_set.hpp"
#include "tests/support/rendered_scene.hpp"

namespace petra {
namespace {

const test::RenderedScene& fixture() {
  static const test::RenderedScene f = [] {
    sim::SceneOptions o = sim::real_scene_set()[25];
    o.edge_supersampling = 2;
    return test::render_for_test(o);
  }();
  return f;
}

struct Run {
  std::vector<std::byte> block;
  Arena arena;
  Result<Proposer> proposer = Error::make(Errc::not_ready, "not created");
};

void create(const test::RenderedScene& f, Run& run) {
  auto budget = eval::ground_proposer_budget(f.rig, PipelineParams{});
  ASSERT_TRUE(budget.ok()) << budget.error().message;
  run.block.resize(Proposer::arena_bytes(*budget, PipelineParams{}));
  run.arena = Arena(run.block);
  run.proposer = Proposer::create(f.rig, *budget, PipelineParams{}, arm::rover_arm_geometry(),
                                  arm::default_joint_limits(), run.arena);
  ASSERT_TRUE(run.proposer.ok()) << run.proposer.error().message;
}

// Angle (deg) and distance (mm) of a plane to the nearest truth facet by angle.
struct FacetError {
  double angle_deg = 180, distance_mm = 1e9;
};
FacetError nearest_facet(const sim::TruthFile& truth, const GrindPlane& p) {
  FacetError best;
  for (const sim::TruthFacet& t : truth.facets) {
    const double a = std::acos(std::clamp(t.normal.dot(p.normal), -1.0, 1.0)) * 180.0 / M_PI;
    if (a < best.angle_deg) best = {a, std::abs(t.normal.dot(p.face_centroid_mm - t.centroid_mm))};
  }
  return best;
}

TEST(ProposeScene, TheTargetRockIsOfferedWithATruePlane) {
  const test::RenderedScene& f = fixture();
  ASSERT_TRUE(f.products.truth.click.has_value());
  Run run;
  create(f, run);
  ASSERT_TRUE(run.proposer.ok());
  auto list = run.proposer->run(f.products.left.image.view(), f.products.right.image.view(),
                                ProposalRequest{}, arm::stow_pose(), {});
  ASSERT_TRUE(list.ok()) << list.error().message;
  const ProposalList& l = **list;
  ASSERT_GE(l.count, 1) << l.empty_reason;
  const int cu = static_cast<int>(f.products.truth.click->x());
  const int cv = static_cast<int>(f.products.truth.click->y());
  const RockProposal* target = nullptr;
  for (int i = 0; i < l.count && target == nullptr; ++i)
    if (l.items[i].rock.roi.contains(cu, cv)) target = &l.items[i];
  ASSERT_NE(target, nullptr) << "no proposal's ROI holds the truth click";
  EXPECT_EQ(target->note, ProposalNote::ok) << eval::proposal_reason(*target);
  EXPECT_EQ(target, &l.items[0]) << "the target rock is not ranked first";
  int offered = 0;
  for (int k = 0; k < target->plane_count; ++k) {
    if (target->planes[k].verdict != PlaneVerdict::accepted ||
        target->reach[k] != arm::ArmReason::ok)
      continue;
    ++offered;
    const FacetError e = nearest_facet(f.truth, target->planes[k]);
    EXPECT_LT(e.angle_deg, 3.0) << "plane " << k + 1;
    EXPECT_LT(e.distance_mm, 2.0) << "plane " << k + 1;
  }
  EXPECT_GE(offered, 1);
}

TEST(ProposeScene, ARequestIsRefusedByFieldName) {
  const test::RenderedScene& f = fixture();
  Run run;
  create(f, run);
  ASSERT_TRUE(run.proposer.ok());
  ProposalRequest bad;
  bad.region = {900, 700, 200, 100};  // past the image's corner
  auto r = run.proposer->run(f.products.left.image.view(), f.products.right.image.view(), bad,
                             arm::stow_pose(), {});
  ASSERT_FALSE(r.ok());
  EXPECT_NE(std::string(r.error().message).find("region"), std::string::npos);
}

}  // namespace
}  // namespace petra
