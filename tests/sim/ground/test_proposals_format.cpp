// `petra tlm` on PROPOSALS, PROPOSAL_PLANES and on PROPOSE's refusals: the
// list and every carried plane readably, the empty reason and the refused
// field by name.
#include "sim/ground/proposals_format.hpp"

#include <gtest/gtest.h>

#include <string>

#include "algo/wire/reasons.hpp"
#include "cmd/commands.hpp"
#include "sim/ground/tlm_format.hpp"

namespace petra::ground {
namespace {

std::string line_of(const tlm::Proposals& p) {
  tlm::TmPacket packet;
  packet.header.primary.apid = static_cast<std::uint16_t>(tlm::Apid::PROPOSALS);
  packet.body = p;
  return format_line(packet);
}

TEST(ProposalsFormat, ListsEachProposalWithItsScoreAndPlane) {
  tlm::Proposals p;
  p.proposal_id = 3;
  p.frame = 9;
  p.count = 2;
  p.candidates = 4;
  p.region_px = {0, 0, 1024, 768};
  p.total_ms = 640;
  p.rank = {1, 2};
  p.roi_px[0] = 300, p.roi_px[1] = 200, p.roi_px[2] = 120, p.roi_px[3] = 90;
  p.click_px[0] = 350, p.click_px[1] = 240;
  p.planes_c = {2, 3};
  p.plane_count = {2, 1};
  p.plane_offered = {1, 0};
  p.score_total = {0.875f, 0.25f};
  p.normal[0] = 0.6f, p.normal[2] = 0.8f;
  p.verdict = {0, 3};
  p.reach = {0, 0};
  p.note = {0, 1};
  const std::string s = line_of(p);
  EXPECT_NE(s.find("proposals 3 on pair 9: 2 listed of 4 rocks detected in (0, 0, 1024 x 768)"),
            std::string::npos)
      << s;
  EXPECT_NE(s.find("#1 roi (300, 200, 120 x 90) click (350, 240)"), std::string::npos) << s;
  EXPECT_NE(s.find("c = 2, ok; score 0.875"), std::string::npos) << s;
  EXPECT_NE(s.find("offered plane normal (0.6000, 0.0000, 0.8000)"), std::string::npos) << s;
  EXPECT_NE(s.find("#2 "), std::string::npos) << s;
  EXPECT_NE(s.find("no_grindable_plane"), std::string::npos) << s;
  EXPECT_NE(s.find("best (not offered) plane"), std::string::npos) << s;
  EXPECT_NE(s.find("too_rough, reach ok"), std::string::npos) << s;
}

TEST(ProposalsFormat, ListsEveryCarriedPlaneByRankAndPlane) {
  tlm::ProposalPlanes p;
  p.proposal_id = 3;
  p.frame = 9;
  p.count = 2;
  p.plane_count = {2, 1};
  constexpr std::size_t kRank2 = PETRA_MAX_PROPOSAL_PLANES;  // slot of rank 2's plane 1
  p.offered[1] = 1, p.offered[kRank2] = 1;                   // rank 1 plane 2, rank 2 plane 1
  p.normal[3 * 1 + 0] = 0.6f, p.normal[3 * 1 + 2] = 0.8f;
  p.centroid_mm[3 * kRank2 + 1] = 250.5f;
  p.reach[0] = 2;
  tlm::TmPacket packet;
  packet.header.primary.apid = static_cast<std::uint16_t>(tlm::Apid::PROPOSAL_PLANES);
  packet.body = p;
  const std::string s = format_line(packet);
  EXPECT_NE(s.find("proposal planes 3 on pair 9: 3 planes of 2 proposals, 2 offered"),
            std::string::npos)
      << s;
  EXPECT_NE(s.find("#1.1 not offered"), std::string::npos) << s;
  EXPECT_NE(s.find("reach beyond_reach"), std::string::npos) << s;
  EXPECT_NE(s.find("#1.2 offered: normal (0.6000, 0.0000, 0.8000)"), std::string::npos) << s;
  EXPECT_NE(s.find("#2.1 offered: normal (0.0000, 0.0000, 0.0000) centroid (0.00, 250.50, 0.00)"),
            std::string::npos)
      << s;
  EXPECT_EQ(s.find("#1.3"), std::string::npos) << s;  // not carried
}

TEST(ProposalsFormat, SaysWhyNothingIsOffered) {
  tlm::Proposals p;
  p.status = 1;
  p.empty_reason = 1;
  EXPECT_NE(line_of(p).find("nothing offered: no_rock"), std::string::npos) << line_of(p);
  p.empty_reason = 4;
  EXPECT_NE(line_of(p).find("none_reachable"), std::string::npos);
  p.status = 2;
  p.reason = static_cast<std::uint8_t>(Reason::PIPELINE_ERROR);
  EXPECT_NE(line_of(p).find("FAILED: PIPELINE_ERROR"), std::string::npos);
}

TEST(ProposalsFormat, RefusalsNameTheProposeField) {
  const auto fc = static_cast<std::uint8_t>(cmd::FunctionCode::PROPOSE);
  const auto out = static_cast<std::uint8_t>(Reason::OUT_OF_RANGE);
  const auto bad = static_cast<std::uint8_t>(Reason::INVALID_ARGUMENT);
  EXPECT_EQ(refusal_detail(fc, out, 5), "field count");
  EXPECT_EQ(refusal_detail(fc, out, 8), "field weight_certainty");
  EXPECT_EQ(refusal_detail(fc, bad, 6), "fields weight_grindable .. weight_size: all 0");
  EXPECT_EQ(refusal_detail(fc, bad, 3).rfind("field w_px: ", 0), 0u);
}

}  // namespace
}  // namespace petra::ground
