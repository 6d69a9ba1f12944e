#include "algo/core/disparity.hpp"

#include <gtest/gtest.h>

namespace petra {
namespace {

TEST(Disparity, Q4RoundTripsToASixteenthOfAPixel) {
  for (double d = -100.0; d <= 300.0; d += 0.37) {
    const std::int16_t q = disparity_q4(d);
    EXPECT_TRUE(is_valid_disparity(q));
    EXPECT_LE(std::abs(disparity_px(q) - d), 0.5 / kDisparityScale + 1e-12) << d;
  }
  EXPECT_FALSE(is_valid_disparity(kInvalidDisparity));
  EXPECT_EQ(disparity_q4(2.0), 32);
  EXPECT_EQ(disparity_q4(-2.0), -32);
}

}  // namespace
}  // namespace petra
