#include "sim/eval/disparity_image.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

namespace petra::eval {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

TEST(DisparityImage, FillTakesTheSmallerNearestValidNeighbourOnTheRow) {
  io::FloatImage d(8, 2);
  const float row0[8] = {kInf, 5, kInf, kInf, 9, kInf, 3, kInf};
  const float row1[8] = {kInf, kInf, kInf, kInf, kInf, kInf, kInf, kInf};
  for (int x = 0; x < 8; ++x) {
    d.data[static_cast<std::size_t>(x)] = row0[x];
    d.data[8 + static_cast<std::size_t>(x)] = row1[x];
  }
  fill_invalid_background(d.view());
  const float expect[8] = {5, 5, 5, 5, 9, 3, 3, 3};  // ends: the only side; middle: the smaller
  for (int x = 0; x < 8; ++x) EXPECT_EQ(d.data[static_cast<std::size_t>(x)], expect[x]) << x;
  for (int x = 0; x < 8; ++x)
    EXPECT_TRUE(std::isinf(d.data[8 + static_cast<std::size_t>(x)]));  // nothing to take
}

TEST(DisparityImage, FillStaysInsideTheArea) {
  io::FloatImage d(6, 1, kInf);
  d.data[1] = 4;
  fill_invalid_background(d.view(), Rect{2, 0, 3, 1});
  EXPECT_TRUE(std::isinf(d.data[0]));
  EXPECT_TRUE(std::isinf(d.data[2]));  // the valid 4 is outside the area
}

TEST(DisparityImage, Q4MapBecomesAFullSizeImageWithInfElsewhere) {
  std::vector<std::int16_t> q{16, kInvalidDisparity, 40, -8};
  ConstDisparityMap m(ImageView<const std::int16_t>(q.data(), 2, 2), Rect{3, 1, 2, 2});
  const io::FloatImage img = to_float_image(m, 6, 4);
  EXPECT_FLOAT_EQ(img.data[1 * 6 + 3], 1.0f);
  EXPECT_TRUE(std::isinf(img.data[1 * 6 + 4]));
  EXPECT_FLOAT_EQ(img.data[2 * 6 + 3], 2.5f);
  EXPECT_FLOAT_EQ(img.data[2 * 6 + 4], -0.5f);
  EXPECT_TRUE(std::isinf(img.data[0]));
}

}  // namespace
}  // namespace petra::eval
