#include "fsw/config.hpp"

#include <gtest/gtest.h>

#include <string>

namespace petra::fsw {
namespace {

Result<FswConfig> parse(const std::string& s) {
  return parse_config(s.data(), s.size(), "/etc/petra");
}

const std::string kMinimal = R"({"uplink":{"key_file":"k.hex"},"camera":{"dir":"/data/pairs"}})";

TEST(Config, MinimalFileGetsDefaultsAndResolvesRelativePaths) {
  auto c = parse(kMinimal);
  ASSERT_TRUE(c.ok()) << c.error().message;
  EXPECT_STREQ(c->key_file.data(), "/etc/petra/k.hex");
  EXPECT_STREQ(c->camera_dir.data(), "/data/pairs");
  EXPECT_EQ(c->cmd_port, 47100);
  EXPECT_EQ(c->tlm_port, 47101);
  EXPECT_EQ(c->cycle_ms, 10u);
  EXPECT_EQ(c->budget.image_width, 1024);
}

TEST(Config, EveryErrorNamesTheField) {
  const struct {
    const char* text;
    const char* names;
  } cases[] = {
      {R"({"camera":{"dir":"x"}})", "uplink"},
      {R"({"uplink":{},"camera":{"dir":"x"}})", "uplink.key_file"},
      {R"({"uplink":{"key_file":"k","port":70000},"camera":{"dir":"x"}})", "uplink.port"},
      {R"({"uplink":{"key_file":"k"},"camera":{"dir":"x"},"loop":{"cycle_ms":0}})",
       "loop.cycle_ms"},
      {R"({"uplink":{"key_file":"k"},"camera":{"dir":"x"},"budget":{"arena_mb":"big"}})",
       "budget.arena_mb"},
      {R"({"uplink":{"key_file":"k"},"camera":{"kind":"v4l2","dir":"x"}})", "camera.kind"},
      {R"({"uplink":{"key_file":"k"}})", "camera"},
      {R"({"uplink":{"key_file":"k"},"camera":{"dir":"x"},)", "json"},
      {R"({"uplink":{"key_file":"k"},"camera":{"dir":"x"},"arm":{"can_interface":"udp:1:0"}})",
       "arm.can_interface 'udp:1:0'"},
  };
  for (const auto& c : cases) {
    auto r = parse(c.text);
    ASSERT_FALSE(r.ok()) << c.text;
    EXPECT_NE(std::string(r.error().message).find(c.names), std::string::npos)
        << r.error().message << " should name " << c.names;
  }
}

TEST(Config, ArmOnCanOverUdpKeepsTheSpec) {
  auto c = parse(
      R"({"uplink":{"key_file":"k"},"camera":{"dir":"x"},"arm":{"can_interface":"udp:47200:47201","mount":[300,100,100,90]}})");
  ASSERT_TRUE(c.ok()) << c.error().message;
  EXPECT_TRUE(c->arm.enabled);
  EXPECT_STREQ(c->arm.can_interface.data(), "udp:47200:47201");
}

}  // namespace
}  // namespace petra::fsw
