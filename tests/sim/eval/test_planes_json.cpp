// planes.json's optional gray_map object (sim/eval/planes_json): written for
// whichever matcher mapped the right view, absent when none did.
#include <gtest/gtest.h>

#include <string>

#include "sim/eval/planes_json.hpp"

namespace petra {
namespace {

TEST(PlanesJson, GrayMapIsWrittenOnlyWhenGiven) {
  EXPECT_EQ(eval::format_planes_json({}).find("gray_map"), std::string::npos);
  const eval::GrayMapQ8 map{312, -5 * 256 - 128};  // x 1.21875, -5.5 levels
  const std::string j = eval::format_planes_json({}, nullptr, &map);
  EXPECT_NE(j.find("\"gray_map\":{\"gain\":1.21875,\"offset\":-5.5}"), std::string::npos) << j;
}

}  // namespace
}  // namespace petra
