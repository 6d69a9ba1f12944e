// The configuration's "arm" section (docs/icd.md, petra-fsw configuration).
#include <gtest/gtest.h>

#include <string>

#include "fsw/config.hpp"

namespace petra::fsw {
namespace {

Result<FswConfig> parse(const std::string& arm) {
  const std::string s = R"({"uplink":{"key_file":"k.hex"},"camera":{"dir":"/data"})" + arm + "}";
  return parse_config(s.data(), s.size(), "/etc/petra");
}

TEST(ArmConfig, AbsentMeansNoArm) {
  auto c = parse("");
  ASSERT_TRUE(c.ok()) << c.error().message;
  EXPECT_FALSE(c->arm.enabled);
}

TEST(ArmConfig, InterfaceAndMountAreRead) {
  auto c = parse(R"(,"arm":{"can_interface":"vcan0","mount":[300,100,100,90]})");
  ASSERT_TRUE(c.ok()) << c.error().message;
  EXPECT_TRUE(c->arm.enabled);
  EXPECT_STREQ(c->arm.can_interface.data(), "vcan0");
  ASSERT_TRUE(c->arm.has_mount);
  EXPECT_DOUBLE_EQ(c->arm.mount[3], 90.0);
  c = parse(R"(,"arm":{"can_interface":"can0"})");
  ASSERT_TRUE(c.ok());
  EXPECT_FALSE(c->arm.has_mount);
  EXPECT_EQ(c->arm.heartbeat_timeout_ms, 0);  // the flight defaults
  c = parse(R"(,"arm":{"can_interface":"can0","heartbeat_timeout_ms":5000})");
  ASSERT_TRUE(c.ok()) << c.error().message;
  EXPECT_EQ(c->arm.heartbeat_timeout_ms, 5000);
  EXPECT_EQ(c->arm.sdo_timeout_ms, 0);  // the flight default
  c = parse(R"(,"arm":{"can_interface":"can0","sdo_timeout_ms":3000})");
  ASSERT_TRUE(c.ok()) << c.error().message;
  EXPECT_EQ(c->arm.sdo_timeout_ms, 3000);
}

TEST(ArmConfig, ErrorsNameTheField) {
  const struct {
    const char* arm;
    const char* field;
  } cases[] = {
      {R"(,"arm":{})", "arm.can_interface"},
      {R"(,"arm":{"can_interface":""})", "arm.can_interface"},
      {R"(,"arm":{"can_interface":"can0","mount":[1,2,3]})", "arm.mount"},
      {R"(,"arm":{"can_interface":"can0","mount":[1,2,"x",4]})", "arm.mount[2]"},
      {R"(,"arm":{"can_interface":"can0","mount":[1,2,3,1e9]})", "arm.mount[3]"},
      {R"(,"arm":"can0")", "arm"},
      {R"(,"arm":{"can_interface":"can0","heartbeat_timeout_ms":100})", "arm.heartbeat_timeout_ms"},
      {R"(,"arm":{"can_interface":"can0","heartbeat_timeout_ms":1e6})", "arm.heartbeat_timeout_ms"},
      {R"(,"arm":{"can_interface":"can0","heartbeat_timeout_ms":300.5})",
       "arm.heartbeat_timeout_ms"},
      {R"(,"arm":{"can_interface":"can0","sdo_timeout_ms":10})", "arm.sdo_timeout_ms"},
      {R"(,"arm":{"can_interface":"can0","sdo_timeout_ms":20000})", "arm.sdo_timeout_ms"},
  };
  for (const auto& c : cases) {
    auto r = parse(c.arm);
    ASSERT_FALSE(r.ok()) << c.arm;
    EXPECT_NE(std::string(r.error().message).find(c.field), std::string::npos) << r.error().message;
  }
}

}  // namespace
}  // namespace petra::fsw
