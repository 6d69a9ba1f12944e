#include "fsw/param_table.hpp"

#include <gtest/gtest.h>

#include <string>

namespace petra::fsw {
namespace {

TEST(ParamTable, StartsAtTheDefinedDefaults) {
  ParamTable t;
  for (const ParamDesc& p : param_table()) {
    double v = -1;
    ASSERT_TRUE(t.get(p.id, v));
    EXPECT_EQ(v, p.default_value) << p.name;
    EXPECT_TRUE(param_value_valid(p, p.default_value))
        << p.name << " default outside its own range";
  }
}

TEST(ParamTable, SetRefusesUnknownOutOfRangeAndFractionalValues) {
  ParamTable t;
  EXPECT_FALSE(t.set(999, 1).ok());
  EXPECT_FALSE(t.set(static_cast<std::uint16_t>(ParamId::HK_PERIOD_MS), 50).ok());
  EXPECT_FALSE(t.set(static_cast<std::uint16_t>(ParamId::HK_PERIOD_MS), 150.5).ok());
  EXPECT_EQ(t.get(ParamId::HK_PERIOD_MS), 1000);
  EXPECT_TRUE(t.set(static_cast<std::uint16_t>(ParamId::SHADOW_FRACTION), 0.25).ok());
  EXPECT_EQ(t.get(ParamId::SHADOW_FRACTION), 0.25);
}

TEST(ParamTable, DefaultsFileSetsByNameAndNamesWhatIsWrong) {
  ParamTable t;
  const std::string good = R"({"HK_PERIOD_MS": 500, "MATCH_METHOD": 1})";
  auto n = t.load_defaults(good.data(), good.size());
  ASSERT_TRUE(n.ok()) << n.error().message;
  EXPECT_EQ(*n, 2);
  EXPECT_EQ(t.get(ParamId::MATCH_METHOD), 1);
  const std::string unknown = R"({"WARP_SPEED": 9})";
  auto bad = t.load_defaults(unknown.data(), unknown.size());
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(std::string(bad.error().message).find("WARP_SPEED"), std::string::npos);
  const std::string range = R"({"MATCH_METHOD": 7})";
  bad = t.load_defaults(range.data(), range.size());
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(std::string(bad.error().message).find("MATCH_METHOD"), std::string::npos);
}

}  // namespace
}  // namespace petra::fsw
