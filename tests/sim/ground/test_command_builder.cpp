#include "sim/ground/command_builder.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>

#include "algo/wire/reasons.hpp"
#include "sim/ground/tlm_format.hpp"
#include "tlm/event_defs.hpp"

namespace petra::ground {
namespace {

TEST(CommandBuilder, BuildsSelectRoiFromFieldWords) {
  auto c = build_command("select_roi", {"x_px=10", "y_px=20", "w_px=100", "h_px=80", "planes=3",
                                        "click_u_px=50", "click_v_px=60"});
  ASSERT_TRUE(c.ok()) << c.error().message;
  EXPECT_EQ(c->code, cmd::FunctionCode::SELECT_ROI);
  const auto& a = std::get<cmd::SelectRoiArgs>(c->args);
  EXPECT_EQ(a.w_px, 100);
  EXPECT_EQ(a.planes, 3);
  EXPECT_EQ(a.has_click, 1);  // implied by the click fields
  EXPECT_EQ(a.click_v_px, 60);
}

TEST(CommandBuilder, RefusesUnknownNamesFieldsAndRangesNamingThem) {
  auto c = build_command("FLY", {});
  ASSERT_FALSE(c.ok());
  EXPECT_NE(std::string(c.error().message).find("FLY"), std::string::npos);
  c = build_command("ARM_GOTO", {"speed=3"});
  ASSERT_FALSE(c.ok());
  EXPECT_NE(std::string(c.error().message).find("speed"), std::string::npos);
  c = build_command("SELECT_ROI", {"planes=9"});
  ASSERT_FALSE(c.ok());
  EXPECT_NE(std::string(c.error().message).find("planes"), std::string::npos);
  c = build_command("SELECT_ROI", {"planes=2.5"});
  EXPECT_FALSE(c.ok());
  c = build_command("SELECT_ROI", {"planes"});
  EXPECT_FALSE(c.ok());
}

TEST(CommandBuilder, EveryFieldIsRequiredExceptTheClick) {
  auto c = build_command("SELECT_ROI", {"x_px=10"});
  ASSERT_FALSE(c.ok());
  EXPECT_NE(std::string(c.error().message).find("missing y_px, w_px, h_px, planes"),
            std::string::npos)
      << c.error().message;
  c = build_command("SELECT_ROI", {"x_px=10", "y_px=20", "w_px=100", "h_px=80", "planes=3"});
  ASSERT_TRUE(c.ok()) << c.error().message;
  EXPECT_EQ(std::get<cmd::SelectRoiArgs>(c->args).has_click, 0);
  c = build_command("SELECT_ROI",
                    {"x_px=10", "y_px=20", "w_px=100", "h_px=80", "planes=3", "has_click=1"});
  EXPECT_FALSE(c.ok());
  c = build_command("ARM_GOTO", {"plane_rank=1"});
  ASSERT_FALSE(c.ok());
  EXPECT_NE(std::string(c.error().message).find("standoff_mm"), std::string::npos);
  c = build_command("SET_PARAM", {"param_id=1", "value=1e9"});
  ASSERT_FALSE(c.ok());
  EXPECT_NE(std::string(c.error().message).find("range"), std::string::npos) << c.error().message;
  EXPECT_TRUE(build_command("NOOP", {}).ok());
  EXPECT_NE(command_usage().find("[click_u_px="), std::string::npos) << command_usage();
}

TEST(CommandBuilder, CounterFileIncreasesEveryTime) {
  const auto path =
      std::filesystem::temp_directory_path() / ("petra_counter_" + std::to_string(::getpid()));
  std::filesystem::remove(path);
  EXPECT_EQ(*next_counter(path.string()), 1u);
  EXPECT_EQ(*next_counter(path.string()), 2u);
  EXPECT_EQ(*next_counter(path.string()), 3u);
  std::filesystem::remove(path);
}

TEST(TlmFormat, EventTextNamesItsArguments) {
  tlm::Event e;
  e.event_id = static_cast<std::uint16_t>(EventId::MODE_CHANGED);
  e.args = {1, 5, 0x31, 0};
  EXPECT_EQ(event_text(e), "mode IDLE -> SAFE (by SET_MODE)");
  e.event_id = rejection_event(Reason::BAD_AUTH);
  e.args = {0x10, 0, 0, 0};
  EXPECT_NE(event_text(e).find("SELECT_ROI rejected: HMAC-SHA256 does not verify"),
            std::string::npos);
}

// The onboard refusal's detail as the operator's names, in every ground view.
TEST(TlmFormat, RefusalDetailsAreNamed) {
  const auto roi = static_cast<std::uint8_t>(cmd::FunctionCode::SELECT_ROI);
  const auto set = static_cast<std::uint8_t>(cmd::FunctionCode::SET_PARAM);
  const auto out_of_range = static_cast<std::uint8_t>(Reason::OUT_OF_RANGE);
  EXPECT_EQ(refusal_detail(roi, out_of_range, 4), "field planes");
  EXPECT_EQ(refusal_detail(roi, static_cast<std::uint8_t>(Reason::INVALID_ARGUMENT), 6),
            "field click_u_px");
  EXPECT_EQ(refusal_detail(set, static_cast<std::uint8_t>(Reason::INVALID_ARGUMENT), 99),
            "unknown parameter id 99");
  EXPECT_EQ(refusal_detail(roi, static_cast<std::uint8_t>(Reason::WRONG_MODE), 5), "in mode SAFE");
  EXPECT_EQ(refusal_detail(roi, static_cast<std::uint8_t>(Reason::BAD_AUTH), 0), "");

  tlm::TmPacket p;
  p.header.primary.apid = static_cast<std::uint16_t>(tlm::Apid::ACK);
  tlm::Ack a;
  a.function_code = roi;
  a.counter = 9;
  a.stage = static_cast<std::uint8_t>(AckStage::REJECTED);
  a.reason = out_of_range;
  a.detail = 4;
  p.body = a;
  EXPECT_NE(format_line(p).find("SELECT_ROI counter 9 REJECTED OUT_OF_RANGE (field planes)"),
            std::string::npos)
      << format_line(p);
  EXPECT_EQ(format_line(p).find("detail"), std::string::npos) << format_line(p);
  EXPECT_NE(format_json(p).find("\"detail_text\":\"field planes\""), std::string::npos)
      << format_json(p);

  tlm::Event e;
  e.event_id = rejection_event(Reason::OUT_OF_RANGE);
  e.args = {roi, 4, 9, 0};
  EXPECT_NE(event_text(e).find("SELECT_ROI rejected: an argument is outside its range"),
            std::string::npos)
      << event_text(e);
  EXPECT_NE(event_text(e).find("(field planes, counter 9)"), std::string::npos) << event_text(e);
}

TEST(TlmFormat, JsonLineCarriesPacketNameAndFields) {
  tlm::TmPacket p;
  p.header.primary.apid = static_cast<std::uint16_t>(tlm::Apid::ACK);
  tlm::Ack a;
  a.function_code = 0x12;
  a.counter = 7;
  a.stage = 3;
  p.body = a;
  const std::string j = format_json(p);
  EXPECT_NE(j.find("\"packet\":\"ACK\""), std::string::npos) << j;
  EXPECT_NE(j.find("\"counter\":7"), std::string::npos) << j;
  EXPECT_NE(format_line(p).find("EVALUATE counter 7 COMPLETED"), std::string::npos)
      << format_line(p);
}

}  // namespace
}  // namespace petra::ground
