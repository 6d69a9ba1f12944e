// planes.json's optional objects (sim/eval/planes_json): gray_map, written for
// whichever matcher mapped the right view, absent when none did; click_region,
// written when the rock was grown from the click.
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

TEST(PlanesJson, ClickRegionIsWrittenOnlyForARockGrownFromTheClick) {
  ReconstructionOutput r;
  EXPECT_EQ(eval::format_planes_json(r).find("click_region\":{"), std::string::npos);
  r.segmentation = SegmentMethod::click_region;
  r.click_region.points = 18973;
  r.click_region.loosened = 1;
  const std::string j = eval::format_planes_json(r);
  EXPECT_NE(j.find("\"click_region\":{\"points\":18973,\"loosened\":1}"), std::string::npos) << j;
}

}  // namespace
}  // namespace petra
