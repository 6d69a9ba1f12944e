// The ground station refuses every malformed command request before signing
// anything, and names the field at fault.
#include <gtest/gtest.h>

#include <string>

#include "sim/gnd/command_request.hpp"

namespace petra::gnd {
namespace {

std::string error_of(const std::string& body) {
  auto r = parse_command_request(body);
  EXPECT_FALSE(r) << body;
  return r ? std::string() : std::string(r.error().message);
}

TEST(CommandRequest, BuildsSelectRoiWithClick) {
  auto c = parse_command_request(
      R"({"command":"SELECT_ROI","args":{"x_px":10,"y_px":20,"w_px":100,"h_px":80,"planes":3,)"
      R"("click_u_px":50,"click_v_px":60}})");
  ASSERT_TRUE(c) << c.error().message;
  EXPECT_EQ(c->code, cmd::FunctionCode::SELECT_ROI);
  const auto& a = std::get<cmd::SelectRoiArgs>(c->args);
  EXPECT_EQ(a.x_px, 10);
  EXPECT_EQ(a.y_px, 20);
  EXPECT_EQ(a.w_px, 100);
  EXPECT_EQ(a.h_px, 80);
  EXPECT_EQ(a.planes, 3);
  EXPECT_EQ(a.has_click, 1);  // set by giving the click
  EXPECT_EQ(a.click_u_px, 50);
  EXPECT_EQ(a.click_v_px, 60);
}

TEST(CommandRequest, CommandNameIsCaseInsensitiveAndArgsOptional) {
  auto c = parse_command_request(R"({"command":"noop"})");
  ASSERT_TRUE(c) << c.error().message;
  EXPECT_EQ(c->code, cmd::FunctionCode::NOOP);
}

TEST(CommandRequest, FloatFieldKeepsItsValue) {
  auto c =
      parse_command_request(R"({"command":"ARM_GOTO","args":{"plane_rank":1,"standoff_mm":42.5}})");
  ASSERT_TRUE(c) << c.error().message;
  const auto& a = std::get<cmd::ArmGotoArgs>(c->args);
  EXPECT_EQ(a.plane_rank, 1);
  EXPECT_FLOAT_EQ(a.standoff_mm, 42.5f);
}

TEST(CommandRequest, RefusesBodiesThatAreNotJsonObjects) {
  EXPECT_NE(error_of("").find("not JSON"), std::string::npos);
  EXPECT_NE(error_of("{\"command\":").find("not JSON"), std::string::npos);
  EXPECT_NE(error_of("[1,2]").find("JSON object"), std::string::npos);
  EXPECT_NE(error_of(std::string(kMaxRequestBytes + 1, ' ')).find("exceeds"), std::string::npos);
}

TEST(CommandRequest, NamesTheMissingOrMistypedMember) {
  EXPECT_NE(error_of("{}").find("command: missing"), std::string::npos);
  EXPECT_NE(error_of(R"({"command":7})").find("command: must be a string"), std::string::npos);
  EXPECT_NE(error_of(R"({"command":"NOOP","args":[1]})").find("args: must be an object"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"command":"NOOP","argz":{}})").find("unknown member 'argz'"),
            std::string::npos);
}

TEST(CommandRequest, NamesTheUnknownCommandOrField) {
  EXPECT_NE(error_of(R"({"command":"LAUNCH"})").find("unknown command 'LAUNCH'"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"command":"EVALUATE","args":{"acquired":1}})").find("no field 'acquired'"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"command":"EVALUATE","args":{"acquire":"yes"}})")
                .find("args.acquire: must be a number"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"command":"EVALUATE","args":{"a=b":1}})").find("bad field name"),
            std::string::npos);
}

// As `petra cmd`: a field left out is refused, not sent as 0.
TEST(CommandRequest, NamesTheMissingFields) {
  EXPECT_NE(error_of(R"({"command":"ARM_GOTO","args":{"plane_rank":1}})")
                .find("ARM_GOTO: missing standoff_mm"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"command":"SELECT_ROI","args":{"x_px":10}})")
                .find("missing y_px, w_px, h_px, planes"),
            std::string::npos);
}

TEST(CommandRequest, NamesTheFieldOutOfRange) {
  EXPECT_NE(error_of(R"({"command":"SELECT_ROI","args":{"x_px":9000}})").find("SELECT_ROI.x_px"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"command":"SELECT_ROI","args":{"planes":9}})").find("SELECT_ROI.planes"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"command":"SELECT_ROI","args":{"w_px":4}})").find("SELECT_ROI.w_px"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"command":"ARM_GOTO","args":{"plane_rank":1.5}})").find("whole numbers"),
            std::string::npos);
  EXPECT_NE(
      error_of(R"({"command":"ARM_GOTO","args":{"standoff_mm":-1}})").find("ARM_GOTO.standoff_mm"),
      std::string::npos);
}

}  // namespace
}  // namespace petra::gnd
