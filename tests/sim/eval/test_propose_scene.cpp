// Rock proposals (algo/propose/proposer) on a realistic scene with two
// touching neighbour rocks (realistic set entry 25: `petra sim scene --real
// --set-index 25`, docs/scene.md "Neighbours"), the whole 1024 x 768 pair, no
// ROI or click given: the target rock is detected and offered, and its
// offered plane lies within 3 deg and 2 mm of one of its truth facets; sent
// back as SELECT_ROI, the proposal gives the same planes; the run takes no
// heap; a region of bare ground gives an empty list with its reason.
// Rendered with fewer edge samples than the set so the check build renders it
// in seconds (as test_eval_roi_fill).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "algo/propose/proposer.hpp"
#include "sim/eval/proposals_json.hpp"
#include "sim/eval/propose_budget.hpp"
#include "sim/scene/scene_set.hpp"
#include "tests/support/heap_counter.hpp"
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

struct ProposerRun {
  std::vector<std::byte> block;
  Arena arena;
  Result<Proposer> proposer = Error::make(Errc::not_ready, "not created");
};

void create(const test::RenderedScene& f, ProposerRun& run) {
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
  ProposerRun run;
  create(f, run);
  ASSERT_TRUE(run.proposer.ok());
  Result<const ProposalList*> list = Error::make(Errc::not_ready, "not run");
  {
    const test::HeapScope heap;  // no heap after create
    list = run.proposer->run(f.products.left.image.view(), f.products.right.image.view(),
                             ProposalRequest{}, arm::stow_pose(), {});
    EXPECT_EQ(heap.allocations(), 0u);
  }
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
  // Sent back as SELECT_ROI (its roi, click and planes_c) to the chain with
  // the same budget: the same planes, bit for bit.
  auto budget = eval::ground_proposer_budget(f.rig, PipelineParams{});
  ASSERT_TRUE(budget.ok());
  std::vector<std::byte> block(Pipeline::arena_bytes(budget->pipeline, PipelineParams{}));
  Arena arena(block);
  auto chain = Pipeline::create(f.rig, budget->pipeline, PipelineParams{}, arena);
  ASSERT_TRUE(chain.ok()) << chain.error().message;
  PipelineRequest select;
  select.roi = target->rock.roi;
  select.has_click = true;
  select.click_u = target->rock.click_u;
  select.click_v = target->rock.click_v;
  select.planes = target->planes_c;
  auto again = chain->run(f.products.left.image.view(), f.products.right.image.view(), select, {});
  ASSERT_TRUE(again.ok()) << again.error().message;
  const GrindResult& g = again->result.planes;
  for (int k = 0; k < std::min(g.accepted, target->plane_count); ++k) {
    EXPECT_EQ(g.planes[k].normal, target->planes[k].normal) << "plane " << k + 1;
    EXPECT_EQ(g.planes[k].centroid_mm, target->planes[k].centroid_mm) << "plane " << k + 1;
  }
  // Last (the list is the proposer's, rewritten by each run): a region of bare near ground (below
  // the rocks) gives an empty list with its reason.
  ProposalRequest bare;
  bare.region = {450, 500, 400, 268};
  auto none = run.proposer->run(f.products.left.image.view(), f.products.right.image.view(), bare,
                                arm::stow_pose(), {});
  ASSERT_TRUE(none.ok()) << none.error().message;
  EXPECT_EQ((*none)->count, 0);
  EXPECT_STREQ((*none)->empty_reason, "no rock stands out of the ground");
}

}  // namespace
}  // namespace petra
