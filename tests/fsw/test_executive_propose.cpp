// PROPOSE end to end in-process (real UDP, file camera, the scripted job
// returning a hand-built ProposalList in place of the proposer): routing,
// the PROPOSALS and PROPOSAL_PLANES packets and picture, SELECT_PROPOSAL,
// ARM_GOTO_PROPOSAL and ARM_GOTO_PROPOSAL_PLANE, and the refusals (wrong
// mode, busy, no proposer, no such proposal).
#include <gtest/gtest.h>

#include <map>

#include "algo/chain/palette.hpp"
#include "tests/fsw/executive_harness.hpp"

namespace petra::test {
namespace {

using cmd::FunctionCode;

GrindPlane plane(PlaneVerdict verdict, Eigen::Vector3d n, Eigen::Vector3d c) {
  GrindPlane g;
  g.verdict = verdict;
  g.normal = n.normalized();
  g.centroid_mm = c;
  g.area_mm2 = 1500;
  g.normal_sigma_deg = 0.5;
  g.offset_sigma_mm = 0.25;
  return g;
}

// Rank 1 offers its second plane (the first is out of reach); rank 2 has
// only a rough face. Camera frames are 160 x 120.
ProposalList two_proposals() {
  ProposalList l;
  l.count = 2;
  l.candidates = 5;
  RockProposal& a = l.items[0];
  a.rock = RockCandidate{Rect{20, 16, 60, 40}, 50, 36, 42.5, 120.0, 900};
  a.planes_c = 2;
  a.plane_count = 2;
  a.planes[0] = plane(PlaneVerdict::accepted, {0, -0.6, 0.8}, {10, 20, 30});
  a.reach[0] = arm::ArmReason::beyond_reach;
  a.planes[1] = plane(PlaneVerdict::accepted, {0.6, 0, 0.8}, {-15.5, 250.25, 80});
  a.reach[1] = arm::ArmReason::ok;
  a.score = ProposalScore{0.8, 0.9, 0.7, 0.6, 0.78};
  RockProposal& b = l.items[1];
  b.rock = RockCandidate{Rect{100, 60, 50, 50}, 120, 80, 15.0, 60.0, 300};
  b.planes_c = 3;
  b.plane_count = 1;
  b.planes[0] = plane(PlaneVerdict::too_rough, {0, 0, 1}, {1, 2, 3});
  b.note = ProposalNote::no_grindable_plane;
  b.score = ProposalScore{0.1, 0.0, 0.5, 0.2, 0.15};
  return l;
}

// Rank 1 carries a third plane, offered too: ARM_GOTO_PROPOSAL still takes
// the second (the best offered), ARM_GOTO_PROPOSAL_PLANE either.
ProposalList three_planes_on_rank_1() {
  ProposalList l = two_proposals();
  RockProposal& a = l.items[0];
  a.plane_count = 3;
  a.planes[2] = plane(PlaneVerdict::accepted, {-0.6, 0, 0.8}, {30.5, 240, 70.25});
  a.reach[2] = arm::ArmReason::ok;
  return l;
}

cmd::ProposeArgs whole_image(int count = 4) {
  cmd::ProposeArgs a;
  a.acquire = 1;
  a.count = static_cast<std::uint8_t>(count);
  a.weight_grindable = 1.0f;
  a.weight_reach = 0.75f;
  a.weight_certainty = 0.5f;
  a.weight_size = 0.25f;
  return a;
}

Reason ack_reason(const ExecutiveHarness& h, std::uint32_t counter) {
  return static_cast<Reason>(h.acks_for(counter).back().reason);
}

// Runs PROPOSE to completion; the PROPOSALS packet it published.
tlm::Proposals propose(ExecutiveHarness& h, const cmd::ProposeArgs& args) {
  const auto c = h.make(FunctionCode::PROPOSE, args);
  h.send(c);
  EXPECT_TRUE(h.cycle_until([&] { return h.has_ack(c.counter, AckStage::COMPLETED); }));
  const auto lists = h.all<tlm::Proposals>();
  return lists.empty() ? tlm::Proposals{} : lists.back();
}

TEST(ExecutivePropose, RoutesToTheProposerAndDownlinksTheRankedList) {
  ExecutiveHarness h;
  h.job.proposals = two_proposals();
  ASSERT_TRUE(h.boot().ok());
  const tlm::Proposals p = propose(h, whole_image(3));
  EXPECT_EQ(h.exec().mode(), Mode::IDLE);
  // The proposer got the operator's request and the arm's pose (stowed: no arm).
  const fsw::EvalRequest& r = h.job.last_request;
  EXPECT_EQ(r.kind, fsw::JobKind::PROPOSE);
  EXPECT_TRUE(r.proposal.region.empty());
  EXPECT_EQ(r.proposal.max_proposals, 3);
  EXPECT_EQ(r.proposal.weights.reach, 0.75);
  EXPECT_EQ(r.arm_pose, arm::stow_pose());

  EXPECT_EQ(p.proposal_id, 1u);
  EXPECT_EQ(p.status, 0);
  EXPECT_EQ(p.empty_reason, 0);
  EXPECT_EQ(p.count, 2);
  EXPECT_EQ(p.candidates, 5);
  EXPECT_EQ(p.region_px, (std::array<std::uint16_t, 4>{0, 0, 160, 120}));
  EXPECT_EQ(p.rank[0], 1);
  EXPECT_EQ(p.rank[1], 2);
  EXPECT_EQ(p.rank[2], 0);
  EXPECT_EQ(p.roi_px[0], 20);
  EXPECT_EQ(p.roi_px[3], 40);
  EXPECT_EQ(p.roi_px[4], 100);
  EXPECT_EQ(p.click_px[0], 50);
  EXPECT_EQ(p.click_px[3], 80);
  EXPECT_EQ(p.height_mm[0], 42.5f);
  EXPECT_EQ(p.planes_c[1], 3);
  EXPECT_EQ(p.note[1], static_cast<std::uint8_t>(ProposalNote::no_grindable_plane));
  EXPECT_FLOAT_EQ(p.score_total[0], 0.78f);
  EXPECT_FLOAT_EQ(p.score_reach[0], 0.9f);
  // Rank 1 shows its offered plane (the second), rank 2 its refused one.
  EXPECT_EQ(p.plane_offered[0], 1);
  EXPECT_FLOAT_EQ(p.normal[0], 0.6f);
  EXPECT_FLOAT_EQ(p.centroid_mm[1], 250.25f);
  EXPECT_EQ(p.reach[0], 0);
  EXPECT_EQ(p.plane_offered[1], 0);
  EXPECT_EQ(p.verdict[1], static_cast<std::uint8_t>(PlaneVerdict::too_rough));
  EXPECT_TRUE(h.has_event(static_cast<std::uint16_t>(EventId::PROPOSE_STARTED)));
  EXPECT_TRUE(h.has_event(static_cast<std::uint16_t>(EventId::PROPOSE_COMPLETED)));
  EXPECT_EQ(p.picture_step, 4);  // THUMB_DECIMATION's default

  // The picture: the left image at THUMB_DECIMATION 4, rank 1's frame in its colour.
  std::map<int, std::vector<std::uint8_t>> chunks;
  std::size_t expected = 0;
  ASSERT_TRUE(h.cycle_until([&] {
    for (const auto& c : h.all<tlm::Product>())
      if (c.product == static_cast<std::uint8_t>(fsw::ProductKind::PROPOSALS)) {
        chunks[c.chunk].assign(c.data.begin(), c.data.begin() + c.data_len);
        expected = c.chunks;
      }
    return expected > 0 && chunks.size() == expected;
  }));
  std::vector<std::uint8_t> rgb;
  for (const auto& [i, bytes] : chunks) rgb.insert(rgb.end(), bytes.begin(), bytes.end());
  ASSERT_EQ(rgb.size(), 40u * 30u * 3u);
  const std::size_t at = (4 * 40 + 5) * 3;  // (20, 16) / 4: the frame's corner
  const palette::Rgb8 want = palette::plane_colour(0);
  EXPECT_EQ(rgb[at], want.r);
  EXPECT_EQ(rgb[at + 1], want.g);
  EXPECT_EQ(rgb[at + 2], want.b);
}

TEST(ExecutivePropose, NoRockIsAClearEmptyResult) {
  ExecutiveHarness h;
  ASSERT_TRUE(h.boot().ok());  // the scripted list is empty, no candidates
  const tlm::Proposals p = propose(h, whole_image());
  EXPECT_EQ(p.status, 1);
  EXPECT_EQ(p.count, 0);
  EXPECT_EQ(p.empty_reason, 1);  // NO_ROCK
  EXPECT_TRUE(h.has_event(static_cast<std::uint16_t>(EventId::PROPOSE_EMPTY)));
  // Only ungrindable rocks: listed, with the reason nothing is offered.
  h.job.proposals = two_proposals();
  h.job.proposals.count = 1;
  h.job.proposals.items[0] = h.job.proposals.items[1];
  const tlm::Proposals q = propose(h, whole_image());
  EXPECT_EQ(q.status, 1);
  EXPECT_EQ(q.count, 1);
  EXPECT_EQ(q.empty_reason, 3);  // NONE_GRINDABLE
}

TEST(ExecutivePropose, SelectProposalSelectsItsRoiClickAndCForEvaluate) {
  ExecutiveHarness h;
  h.job.proposals = two_proposals();
  ASSERT_TRUE(h.boot().ok());
  const tlm::Proposals p = propose(h, whole_image());
  cmd::SelectProposalArgs pick;
  pick.proposal_id = p.proposal_id;
  pick.rank = 1;
  const auto sel = h.make(FunctionCode::SELECT_PROPOSAL, pick);
  h.send(sel);
  const auto eval = h.make(FunctionCode::EVALUATE, cmd::EvaluateArgs{0});
  h.send(eval);
  ASSERT_TRUE(h.cycle_until([&] { return h.has_ack(eval.counter, AckStage::COMPLETED); }));
  EXPECT_TRUE(h.has_ack(sel.counter, AckStage::COMPLETED));
  EXPECT_TRUE(h.has_event(static_cast<std::uint16_t>(EventId::PROPOSAL_SELECTED)));
  const PipelineRequest& s = h.job.last_request.selection;
  EXPECT_EQ(s.roi, (Rect{20, 16, 60, 40}));
  EXPECT_TRUE(s.has_click);
  EXPECT_EQ(s.click_u, 50);
  EXPECT_EQ(s.click_v, 36);
  EXPECT_EQ(s.planes, 2);

  // Another list's id, or a rank beyond the list: NO_SUCH_PROPOSAL.
  for (auto [id, rank] : {std::pair{p.proposal_id + 1, 1}, std::pair{p.proposal_id, 3}}) {
    pick.proposal_id = id;
    pick.rank = static_cast<std::uint8_t>(rank);
    const auto bad = h.make(FunctionCode::SELECT_PROPOSAL, pick);
    h.send(bad);
    ASSERT_TRUE(h.cycle_until([&] { return h.has_ack(bad.counter, AckStage::FAILED); }));
    EXPECT_EQ(ack_reason(h, bad.counter), Reason::NO_SUCH_PROPOSAL);
  }
}

TEST(ExecutivePropose, APickBeyondTheRoiBudgetIsRefusedAsSelectRoiWouldBe) {
  ExecutiveHarness h;
  h.job.proposals = two_proposals();
  h.job.job_limits = fsw::JobLimits{56, 0, 0};  // rank 1's ROI is 60 px wide
  ASSERT_TRUE(h.boot().ok());
  const tlm::Proposals p = propose(h, whole_image());
  cmd::SelectProposalArgs pick;
  pick.proposal_id = p.proposal_id;
  pick.rank = 1;
  const auto sel = h.make(FunctionCode::SELECT_PROPOSAL, pick);
  h.send(sel);
  ASSERT_TRUE(h.cycle_until([&] { return h.has_ack(sel.counter, AckStage::REJECTED); }));
  EXPECT_EQ(ack_reason(h, sel.counter), Reason::ROI_TOO_WIDE);
  EXPECT_EQ(h.acks_for(sel.counter).back().detail, 56);
  pick.rank = 2;  // 50 px: fine
  const auto ok = h.make(FunctionCode::SELECT_PROPOSAL, pick);
  h.send(ok);
  ASSERT_TRUE(h.cycle_until([&] { return h.has_ack(ok.counter, AckStage::COMPLETED); }));
}

TEST(ExecutivePropose, RefusedWhileAnEvaluationRunsOrUnwinds) {
  ExecutiveHarness h;
  h.job.hold = true;
  h.job.ignore_cancel = true;
  ASSERT_TRUE(h.boot().ok());
  h.send(h.make(FunctionCode::SELECT_ROI, roi(0, 0, 50, 50, 2)));
  const auto eval = h.make(FunctionCode::EVALUATE, cmd::EvaluateArgs{1});
  h.send(eval);
  ASSERT_TRUE(h.cycle_until([&] { return h.job.runs.load() == 1; }));
  const auto during = h.make(FunctionCode::PROPOSE, whole_image());
  h.send(during);
  ASSERT_TRUE(h.cycle_until([&] { return h.has_ack(during.counter, AckStage::REJECTED); }));
  EXPECT_EQ(ack_reason(h, during.counter), Reason::WRONG_MODE);
  EXPECT_EQ(h.acks_for(during.counter).back().detail, static_cast<std::uint16_t>(Mode::EVALUATE));
  // Aborted but still unwinding on the worker: BUSY, and nothing changed.
  const auto abort = h.make(FunctionCode::ABORT);
  h.send(abort);
  ASSERT_TRUE(h.cycle_until([&] { return h.has_ack(abort.counter, AckStage::COMPLETED); }));
  const auto unwinding = h.make(FunctionCode::PROPOSE, whole_image());
  h.send(unwinding);
  ASSERT_TRUE(h.cycle_until([&] { return h.has_ack(unwinding.counter, AckStage::REJECTED); }));
  EXPECT_EQ(ack_reason(h, unwinding.counter), Reason::BUSY);
  EXPECT_EQ(h.job.runs.load(), 1);
  h.job.release();
  ASSERT_TRUE(h.cycle_until([&] { return !h.exec().evaluation_running(); }));
  const tlm::Proposals p = propose(h, whole_image());
  EXPECT_EQ(p.proposal_id, 1u);  // the refused ones used no id
}

TEST(ExecutivePropose, AbortStopsAProposalRun) {
  ExecutiveHarness h;
  h.job.hold = true;
  ASSERT_TRUE(h.boot().ok());
  const auto c = h.make(FunctionCode::PROPOSE, whole_image());
  h.send(c);
  ASSERT_TRUE(h.cycle_until([&] { return h.job.runs.load() == 1; }));
  EXPECT_EQ(h.exec().mode(), Mode::EVALUATE);
  const auto eval = h.make(FunctionCode::EVALUATE, cmd::EvaluateArgs{0});
  h.send(eval);  // one run at a time
  ASSERT_TRUE(h.cycle_until([&] { return h.has_ack(eval.counter, AckStage::REJECTED); }));
  EXPECT_EQ(ack_reason(h, eval.counter), Reason::WRONG_MODE);
  h.send(h.make(FunctionCode::ABORT));
  ASSERT_TRUE(h.cycle_until([&] { return h.has_ack(c.counter, AckStage::FAILED); }));
  EXPECT_EQ(ack_reason(h, c.counter), Reason::ABORTED);
  EXPECT_TRUE(h.has_event(static_cast<std::uint16_t>(EventId::PROPOSE_ABORTED)));
  EXPECT_EQ(h.exec().mode(), Mode::IDLE);
  ASSERT_TRUE(h.cycle_until([&] { return h.job.saw_cancel.load(); }));
  EXPECT_TRUE(h.all<tlm::Proposals>().empty());
}

TEST(ExecutivePropose, WithoutAProposerOrAFrameItFailsWithTheReason) {
  ExecutiveHarness h;
  h.job.proposes = false;
  ASSERT_TRUE(h.boot().ok());
  const auto c = h.make(FunctionCode::PROPOSE, whole_image());
  h.send(c);
  ASSERT_TRUE(h.cycle_until([&] { return h.has_ack(c.counter, AckStage::FAILED); }));
  EXPECT_EQ(ack_reason(h, c.counter), Reason::NO_PROPOSER);
  h.job.proposes = true;
  cmd::ProposeArgs no_pair = whole_image();
  no_pair.acquire = 0;
  const auto d = h.make(FunctionCode::PROPOSE, no_pair);
  h.send(d);
  ASSERT_TRUE(h.cycle_until([&] { return h.has_ack(d.counter, AckStage::FAILED); }));
  EXPECT_EQ(ack_reason(h, d.counter), Reason::NO_FRAME);
  EXPECT_EQ(h.exec().mode(), Mode::IDLE);
}

// An arm that records its goal and reaches it at once.
class RecordingArm final : public fsw::ArmPort {
 public:
  fsw::ArmTarget goal;
  int gotos = 0;
  Status start_goto(const fsw::ArmTarget& t) override {
    goal = t;
    ++gotos;
    return {};
  }
  Status start_stow() override { return {}; }
  fsw::ArmProgress poll() override {
    return gotos > 0 ? fsw::ArmProgress::REACHED : fsw::ArmProgress::IDLE;
  }
  void quick_stop() override {}
};

TEST(ExecutivePropose, ArmGotoProposalTargetsTheOfferedPlaneThroughTheArmsChecks) {
  ExecutiveHarness h;
  RecordingArm arm;
  h.arm = &arm;
  h.job.proposals = two_proposals();
  ASSERT_TRUE(h.boot().ok());
  const tlm::Proposals p = propose(h, whole_image());
  cmd::ArmGotoProposalArgs a;
  a.proposal_id = p.proposal_id;
  a.rank = 2;  // no offered plane
  a.standoff_mm = 40.0f;
  const auto refused = h.make(FunctionCode::ARM_GOTO_PROPOSAL, a);
  h.send(refused);
  ASSERT_TRUE(h.cycle_until([&] { return h.has_ack(refused.counter, AckStage::FAILED); }));
  EXPECT_EQ(ack_reason(h, refused.counter), Reason::NO_SUCH_PROPOSAL);
  EXPECT_EQ(arm.gotos, 0);
  a.rank = 1;
  const auto go = h.make(FunctionCode::ARM_GOTO_PROPOSAL, a);
  h.send(go);
  ASSERT_TRUE(h.cycle_until([&] { return h.has_ack(go.counter, AckStage::COMPLETED); }));
  ASSERT_EQ(arm.gotos, 1);
  const GrindPlane& want = h.job.proposals.items[0].planes[1];  // the offered one
  EXPECT_EQ(arm.goal.normal[0], want.normal.x());
  EXPECT_EQ(arm.goal.centroid_mm[1], want.centroid_mm.y());
  EXPECT_EQ(arm.goal.standoff_mm, 40.0);
}

TEST(ExecutivePropose, ProposalPlanesFollowTheListWithEveryCarriedPlane) {
  ExecutiveHarness h;
  h.job.proposals = three_planes_on_rank_1();
  ASSERT_TRUE(h.boot().ok());
  const tlm::Proposals p = propose(h, whole_image());
  const auto all = h.all<tlm::ProposalPlanes>();
  ASSERT_EQ(all.size(), 1u);
  const tlm::ProposalPlanes& q = all[0];
  EXPECT_EQ(q.proposal_id, p.proposal_id);
  EXPECT_EQ(q.frame, p.frame);
  EXPECT_EQ(q.count, 2);
  EXPECT_EQ(q.plane_count[0], 3);
  EXPECT_EQ(q.plane_count[1], 1);
  EXPECT_EQ(q.plane_count[2], 0);
  // Slot P i + k: rank i + 1's plane k + 1 (P plane slots per proposal).
  constexpr std::size_t kRank2 = PETRA_MAX_PROPOSAL_PLANES;
  EXPECT_EQ(q.offered[0], 0);  // out of reach
  EXPECT_EQ(q.reach[0], static_cast<std::uint8_t>(arm::ArmReason::beyond_reach));
  EXPECT_EQ(q.offered[1], 1);
  EXPECT_EQ(q.offered[2], 1);
  EXPECT_FLOAT_EQ(q.normal[3 * 2 + 0], -0.6f);
  EXPECT_FLOAT_EQ(q.centroid_mm[3 * 2 + 2], 70.25f);
  EXPECT_FLOAT_EQ(q.area_mm2[2], 1500.0f);
  EXPECT_EQ(q.area_mm2[3], 0.0f);  // rank 1 carries three planes
  EXPECT_EQ(q.offered[kRank2], 0);
  EXPECT_EQ(q.verdict[kRank2], static_cast<std::uint8_t>(PlaneVerdict::too_rough));
  EXPECT_FLOAT_EQ(q.centroid_mm[3 * kRank2 + 2], 3.0f);
  EXPECT_EQ(q.area_mm2[kRank2 + 1], 0.0f);  // rank 2 carries one plane
  // PROPOSALS still shows rank 1's best offered plane, the second.
  EXPECT_FLOAT_EQ(p.normal[0], 0.6f);
}

TEST(ExecutivePropose, ArmGotoProposalPlaneTakesAnyOfferedPlaneAndRefusesTheRest) {
  ExecutiveHarness h;
  RecordingArm arm;
  h.arm = &arm;
  h.job.proposals = three_planes_on_rank_1();
  ASSERT_TRUE(h.boot().ok());
  const tlm::Proposals p = propose(h, whole_image());
  auto refused = [&](std::uint32_t id, int rank, int plane) {
    cmd::ArmGotoProposalPlaneArgs a;
    a.proposal_id = id;
    a.rank = static_cast<std::uint8_t>(rank);
    a.plane = static_cast<std::uint8_t>(plane);
    a.standoff_mm = 40.0f;
    const auto c = h.make(FunctionCode::ARM_GOTO_PROPOSAL_PLANE, a);
    h.send(c);
    EXPECT_TRUE(h.cycle_until([&] { return h.has_ack(c.counter, AckStage::FAILED); }));
    return ack_reason(h, c.counter);
  };
  EXPECT_EQ(refused(p.proposal_id, 1, 1), Reason::NO_SUCH_PROPOSAL);  // out of reach
  EXPECT_EQ(refused(p.proposal_id, 2, 1), Reason::NO_SUCH_PROPOSAL);  // too rough
  EXPECT_EQ(refused(p.proposal_id, 2, 2), Reason::NO_SUCH_PROPOSAL);  // not carried
  EXPECT_EQ(refused(p.proposal_id + 1, 1, 3), Reason::NO_SUCH_PROPOSAL);
  EXPECT_EQ(arm.gotos, 0);
  cmd::ArmGotoProposalPlaneArgs a;
  a.proposal_id = p.proposal_id;
  a.rank = 1;
  a.plane = 3;
  a.standoff_mm = 60.0f;
  const auto go = h.make(FunctionCode::ARM_GOTO_PROPOSAL_PLANE, a);
  h.send(go);
  ASSERT_TRUE(h.cycle_until([&] { return h.has_ack(go.counter, AckStage::COMPLETED); }));
  ASSERT_EQ(arm.gotos, 1);
  const GrindPlane& want = h.job.proposals.items[0].planes[2];
  EXPECT_EQ(arm.goal.normal[0], want.normal.x());
  EXPECT_EQ(arm.goal.centroid_mm[2], want.centroid_mm.z());
  EXPECT_EQ(arm.goal.standoff_mm, 60.0);
}

}  // namespace
}  // namespace petra::test
