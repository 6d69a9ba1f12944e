#include "sim/ground/command_builder.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>

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
