// PROPOSE, SELECT_PROPOSAL and ARM_GOTO_PROPOSAL at the edge: signed packets
// round trip, every field's bounds (inclusive ends pass, one step beyond is
// refused naming the field), the region and weight consistency checks, and
// the selection checks SELECT_PROPOSAL shares with SELECT_ROI.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "cmd/command_packet.hpp"
#include "cmd/validator.hpp"

namespace petra::cmd {
namespace {

AuthKey propose_test_key() {
  AuthKey k;
  for (std::size_t i = 0; i < k.bytes.size(); ++i) k.bytes[i] = static_cast<std::uint8_t>(3 + i);
  return k;
}

class ProposeCommand : public ::testing::Test {
 protected:
  void SetUp() override { ASSERT_TRUE(auth_init().ok()); }
  ValidationContext ctx() const {
    ValidationContext c;
    c.key = &key_;
    c.last_counter = 10;
    c.mode = Mode::IDLE;
    c.image_width = 1024;
    c.image_height = 768;
    c.max_roi_width = 512;
    c.max_roi_height = 384;
    return c;
  }
  Verdict validate(const Args& args, FunctionCode code, Mode mode = Mode::IDLE) {
    std::vector<std::uint8_t> out(kMaxCommandBytes);
    auto n = encode_command_packet(Command{code, ++counter_, args}, 1, key_, out);
    EXPECT_TRUE(n.ok());
    out.resize(n.ok() ? *n : 0);
    ValidationContext c = ctx();
    c.last_counter = counter_ - 1;
    c.mode = mode;
    return validate_command(out, c);
  }
  Verdict propose(const ProposeArgs& a) { return validate(a, FunctionCode::PROPOSE); }
  static ProposeArgs good() {
    ProposeArgs a;
    a.count = 4;
    a.weight_grindable = 1.0f;
    a.weight_reach = 1.0f;
    a.weight_certainty = 0.5f;
    a.weight_size = 0.25f;
    return a;  // the whole image
  }
  // The field a refusal names, as `petra tlm` and the ground station show it.
  static std::string field(const Verdict& v) { return ProposeArgs::fields()[v.detail].name; }
  AuthKey key_ = propose_test_key();
  std::uint32_t counter_ = 10;
};

TEST_F(ProposeCommand, RoundTripsEveryFieldThroughASignedPacket) {
  ProposeArgs a = good();
  a.acquire = 1;
  a.x_px = 100;
  a.y_px = 60;
  a.w_px = 700;
  a.h_px = 500;
  a.count = 8;
  a.weight_certainty = 0.0f;
  const Verdict v = propose(a);
  ASSERT_TRUE(v.ok()) << reason_name(v.reason) << " " << v.detail;
  const auto& d = std::get<ProposeArgs>(v.command.args);
  EXPECT_EQ(d.acquire, 1);
  EXPECT_EQ(d.x_px, 100);
  EXPECT_EQ(d.y_px, 60);
  EXPECT_EQ(d.w_px, 700);
  EXPECT_EQ(d.h_px, 500);
  EXPECT_EQ(d.count, 8);
  EXPECT_EQ(d.weight_grindable, 1.0f);
  EXPECT_EQ(d.weight_reach, 1.0f);
  EXPECT_EQ(d.weight_certainty, 0.0f);
  EXPECT_EQ(d.weight_size, 0.25f);
  EXPECT_EQ(ProposeArgs::wire_bytes(), 26u);
}

// One step beyond each end of each field's range is OUT_OF_RANGE naming it.
TEST_F(ProposeCommand, EveryFieldOutsideItsRangeIsRefusedByName) {
  struct Case {
    const char* name;
    void (*set)(ProposeArgs&);
  };
  const Case cases[] = {
      {"acquire", [](ProposeArgs& a) { a.acquire = 2; }},
      {"x_px", [](ProposeArgs& a) { a.x_px = 8192; }},
      {"y_px", [](ProposeArgs& a) { a.y_px = 8192; }},
      {"w_px", [](ProposeArgs& a) { a.w_px = 8193; }},
      {"h_px", [](ProposeArgs& a) { a.h_px = 8193; }},
      {"count", [](ProposeArgs& a) { a.count = 0; }},
      {"count", [](ProposeArgs& a) { a.count = 9; }},
      {"weight_grindable", [](ProposeArgs& a) { a.weight_grindable = 1.0001f; }},
      {"weight_grindable", [](ProposeArgs& a) { a.weight_grindable = -0.0001f; }},
      {"weight_reach", [](ProposeArgs& a) { a.weight_reach = 2.0f; }},
      {"weight_reach", [](ProposeArgs& a) { a.weight_reach = -1.0f; }},
      {"weight_certainty",
       [](ProposeArgs& a) { a.weight_certainty = std::numeric_limits<float>::quiet_NaN(); }},
      {"weight_size",
       [](ProposeArgs& a) { a.weight_size = std::numeric_limits<float>::infinity(); }},
  };
  for (const Case& c : cases) {
    ProposeArgs a = good();
    c.set(a);
    const Verdict v = propose(a);
    EXPECT_EQ(v.reason, Reason::OUT_OF_RANGE) << c.name;
    EXPECT_EQ(field(v), c.name);
  }
  ProposeArgs edge = good();  // the inclusive ends pass
  edge.count = 1;
  edge.weight_grindable = 0.0f;
  edge.weight_reach = 0.0f;
  edge.weight_certainty = 0.0f;
  edge.weight_size = 1.0f;
  EXPECT_TRUE(propose(edge).ok());
  edge.count = 8;
  EXPECT_TRUE(propose(edge).ok());
}

TEST_F(ProposeCommand, ARegionOutsideTheImageOrTooSmallIsRefusedByField) {
  struct Case {
    std::uint16_t x, y, w, h;
    const char* field;
  };
  const Case cases[] = {
      {5, 0, 0, 0, "x_px"},         // 0 x 0 is the whole image: x, y must be 0 too
      {0, 5, 0, 0, "y_px"},         //
      {0, 0, 100, 0, "h_px"},       // one side 0
      {0, 0, 31, 100, "w_px"},      // below 32 px
      {0, 0, 100, 31, "h_px"},      //
      {1000, 0, 100, 100, "w_px"},  // 1000 + 100 > 1024
      {1024, 0, 100, 100, "x_px"},  // starts outside
      {0, 700, 100, 100, "h_px"},   // 700 + 100 > 768
      {0, 800, 100, 100, "y_px"},   //
  };
  for (const Case& c : cases) {
    ProposeArgs a = good();
    a.x_px = c.x;
    a.y_px = c.y;
    a.w_px = c.w;
    a.h_px = c.h;
    const Verdict v = propose(a);
    EXPECT_EQ(v.reason, Reason::INVALID_ARGUMENT) << c.x << "," << c.y << " " << c.w << "x" << c.h;
    EXPECT_EQ(field(v), c.field);
  }
  ProposeArgs corner = good();  // the region may touch the image's edges
  corner.x_px = 1024 - 32;
  corner.y_px = 768 - 32;
  corner.w_px = 32;
  corner.h_px = 32;
  EXPECT_TRUE(propose(corner).ok());
}

TEST_F(ProposeCommand, AllWeightsZeroIsRefused) {
  ProposeArgs a = good();
  a.weight_grindable = a.weight_reach = a.weight_certainty = a.weight_size = 0.0f;
  const Verdict v = propose(a);
  EXPECT_EQ(v.reason, Reason::INVALID_ARGUMENT);
  EXPECT_EQ(field(v), "weight_grindable");
}

TEST_F(ProposeCommand, OnlyInIdle) {
  for (Mode m : {Mode::EVALUATE, Mode::ARM_MOVING, Mode::SAFE}) {
    const Verdict v = validate(good(), FunctionCode::PROPOSE, m);
    EXPECT_EQ(v.reason, Reason::WRONG_MODE) << mode_name(m);
    EXPECT_EQ(v.detail, static_cast<std::uint16_t>(m));
  }
  SelectProposalArgs s;
  s.proposal_id = 1;
  s.rank = 1;
  EXPECT_EQ(validate(s, FunctionCode::SELECT_PROPOSAL, Mode::EVALUATE).reason, Reason::WRONG_MODE);
}

TEST_F(ProposeCommand, ProposalPicksHaveRankedBounds) {
  SelectProposalArgs s;
  s.proposal_id = 7;
  s.rank = 8;
  EXPECT_TRUE(validate(s, FunctionCode::SELECT_PROPOSAL).ok());
  s.rank = 0;  // ranks count from 1, as listed
  Verdict v = validate(s, FunctionCode::SELECT_PROPOSAL);
  EXPECT_EQ(v.reason, Reason::OUT_OF_RANGE);
  EXPECT_EQ(v.detail, 1);
  s.rank = 1;
  s.proposal_id = 0;  // ids start at 1: 0 is "no list"
  EXPECT_EQ(validate(s, FunctionCode::SELECT_PROPOSAL).reason, Reason::OUT_OF_RANGE);
  ArmGotoProposalArgs g;
  g.proposal_id = 7;
  g.rank = 2;
  g.standoff_mm = 301.0f;
  v = validate(g, FunctionCode::ARM_GOTO_PROPOSAL);
  EXPECT_EQ(v.reason, Reason::OUT_OF_RANGE);
  EXPECT_EQ(v.detail, 2);
  g.standoff_mm = 50.0f;
  EXPECT_TRUE(validate(g, FunctionCode::ARM_GOTO_PROPOSAL).ok());
}

// The checks SELECT_PROPOSAL applies on board to the proposal's ROI are SELECT_ROI's.
TEST_F(ProposeCommand, SelectionRefusalIsSelectRoisCheck) {
  SelectRoiArgs roi;
  roi.x_px = 100;
  roi.y_px = 100;
  roi.w_px = 300;
  roi.h_px = 200;
  roi.planes = 2;
  roi.has_click = 1;
  roi.click_u_px = 250;
  roi.click_v_px = 200;
  EXPECT_EQ(selection_refusal(roi, ctx()).reason, Reason::NONE);
  SelectRoiArgs wide = roi;
  wide.w_px = 600;  // beyond the budget's 512
  EXPECT_EQ(selection_refusal(wide, ctx()).reason, Reason::ROI_TOO_WIDE);
  EXPECT_EQ(selection_refusal(wide, ctx()).detail, 512);
  SelectRoiArgs off = roi;
  off.click_u_px = 50;
  EXPECT_EQ(selection_refusal(off, ctx()).reason, Reason::INVALID_ARGUMENT);
  EXPECT_EQ(selection_refusal(off, ctx()).detail, 6);
  SelectRoiArgs outside = roi;
  outside.x_px = 900;
  EXPECT_EQ(selection_refusal(outside, ctx()).reason, Reason::INVALID_ARGUMENT);
  SelectRoiArgs none = roi;
  none.planes = 0;
  EXPECT_EQ(selection_refusal(none, ctx()).reason, Reason::OUT_OF_RANGE);
  EXPECT_EQ(selection_refusal(none, ctx()).detail, 4);
}

}  // namespace
}  // namespace petra::cmd
