// The ground station's proposal pick: a point of the left image to the
// proposal under it, and the command that takes it (SELECT_PROPOSAL, or
// SELECT_ROI with the proposal's ROI, click and c), from the request body.
#include "sim/gnd/proposal_pick.hpp"

#include <gtest/gtest.h>

#include <string>

namespace petra::gnd {
namespace {

// Two listed proposals; rank 2's ROI overlaps rank 1's on its left.
tlm::Proposals two() {
  tlm::Proposals p;
  p.proposal_id = 12;
  p.count = 2;
  p.roi_px[0] = 300, p.roi_px[1] = 200, p.roi_px[2] = 120, p.roi_px[3] = 90;
  p.click_px[0] = 350, p.click_px[1] = 240;
  p.planes_c[0] = 2;
  p.roi_px[4] = 250, p.roi_px[5] = 210, p.roi_px[6] = 80, p.roi_px[7] = 60;
  p.click_px[2] = 280, p.click_px[3] = 230;
  p.planes_c[1] = 3;
  p.roi_px[8] = 0, p.roi_px[9] = 0, p.roi_px[10] = 900, p.roi_px[11] = 700;  // beyond count
  p.note[1] = 3;
  p.reach[1] = 2;
  return p;
}

TEST(ProposalPick, APointPicksTheBestRankedProposalUnderIt) {
  const tlm::Proposals p = two();
  EXPECT_EQ(proposal_at(p, 350, 240), 1);
  EXPECT_EQ(proposal_at(p, 310, 220), 1);  // in both: the better rank
  EXPECT_EQ(proposal_at(p, 260, 220), 2);
  EXPECT_EQ(proposal_at(p, 420, 240), std::nullopt);  // right edge is outside (x + w)
  EXPECT_EQ(proposal_at(p, 10, 10), std::nullopt);    // only the listed count counts
}

TEST(ProposalPick, SelectProposalCarriesTheListAndRank) {
  auto c = pick_command(two(), 2, PickAs::SELECT_PROPOSAL);
  ASSERT_TRUE(c.ok()) << c.error().message;
  EXPECT_EQ(c->code, cmd::FunctionCode::SELECT_PROPOSAL);
  const auto& a = std::get<cmd::SelectProposalArgs>(c->args);
  EXPECT_EQ(a.proposal_id, 12u);
  EXPECT_EQ(a.rank, 2);
  EXPECT_EQ(a.out_of_range(), -1);
}

TEST(ProposalPick, SelectRoiCarriesTheProposalsRoiClickAndC) {
  auto c = pick_command(two(), 1, PickAs::SELECT_ROI);
  ASSERT_TRUE(c.ok()) << c.error().message;
  EXPECT_EQ(c->code, cmd::FunctionCode::SELECT_ROI);
  const auto& a = std::get<cmd::SelectRoiArgs>(c->args);
  EXPECT_EQ(a.x_px, 300);
  EXPECT_EQ(a.y_px, 200);
  EXPECT_EQ(a.w_px, 120);
  EXPECT_EQ(a.h_px, 90);
  EXPECT_EQ(a.planes, 2);
  EXPECT_EQ(a.has_click, 1);
  EXPECT_EQ(a.click_u_px, 350);
  EXPECT_EQ(a.click_v_px, 240);
  tlm::Proposals no_chain = two();
  no_chain.planes_c[0] = 0;  // the chain never ran on it: no c to select
  auto bad = pick_command(no_chain, 1, PickAs::SELECT_ROI);
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(std::string(bad.error().message).find("rank"), std::string::npos);
}

TEST(ProposalPick, RequestBodiesPickByPointOrRankAndRefuseByMember) {
  const tlm::Proposals p = two();
  auto by_point = parse_pick_request(R"({"u": 260, "v": 220})", &p);
  ASSERT_TRUE(by_point.ok()) << by_point.error().message;
  EXPECT_EQ(std::get<cmd::SelectProposalArgs>(by_point->args).rank, 2);
  auto by_rank = parse_pick_request(R"({"rank": 1, "as": "select_roi"})", &p);
  ASSERT_TRUE(by_rank.ok()) << by_rank.error().message;
  EXPECT_EQ(std::get<cmd::SelectRoiArgs>(by_rank->args).click_u_px, 350);

  struct Case {
    const char* body;
    const char* names;
  };
  const Case refused[] = {
      {R"({"u": 10, "v": 10})", "u, v"},      // on no proposal
      {R"({"rank": 3})", "rank"},             // beyond the list
      {R"({"u": 260})", "v"},                 // missing
      {R"({"u": "a", "v": 1})", "u"},         // not a number
      {R"({"rank": 1, "as": "arm"})", "as"},  // unknown kind
      {"[1]", "request"},                     // not an object
  };
  for (const Case& c : refused) {
    auto r = parse_pick_request(c.body, &p);
    ASSERT_FALSE(r.ok()) << c.body;
    EXPECT_EQ(std::string(r.error().message).rfind(c.names, 0), 0u)
        << c.body << ": " << r.error().message;
  }
  auto none = parse_pick_request(R"({"rank": 1})", nullptr);
  ASSERT_FALSE(none.ok());
  EXPECT_NE(std::string(none.error().message).find("PROPOSE"), std::string::npos);
}

TEST(ProposalPick, NamesForThePage) {
  const std::string j = proposals_names_json(two());
  EXPECT_NE(j.find(R"("empty_reason":"none")"), std::string::npos) << j;
  EXPECT_NE(j.find(R"("notes":["ok","unreachable"])"), std::string::npos) << j;
  EXPECT_NE(j.find(R"("verdicts":["grindable","grindable"])"), std::string::npos) << j;
  EXPECT_NE(j.find(R"("reaches":["ok","beyond_reach"])"), std::string::npos) << j;
}

}  // namespace
}  // namespace petra::gnd
