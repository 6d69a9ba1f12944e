#include "algo/stereo/downsample.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace petra {
namespace {

TEST(Downsample, BlockMeansRounded) {
  std::vector<std::uint8_t> src(8 * 6);
  for (int y = 0; y < 6; ++y)
    for (int x = 0; x < 8; ++x)
      src[static_cast<std::size_t>(y) * 8 + x] = static_cast<std::uint8_t>(10 * x + y);
  std::vector<std::uint8_t> dst(4 * 3, 0);
  ASSERT_TRUE(downsample_box(ConstGray8View(src.data(), 8, 6), Rect{0, 0, 8, 6}, 2,
                             Gray8View(dst.data(), 4, 3))
                  .ok());
  // Block (0,0): 0, 10, 1, 11 -> 5.5 -> 6 (rounded half up).
  EXPECT_EQ(dst[0], 6);
  // Block (3,2): x 6,7 y 4,5: 64, 74, 65, 75 -> 69.5 -> 70.
  EXPECT_EQ(dst[2 * 4 + 3], 70);
  // A region writes only its whole blocks.
  std::vector<std::uint8_t> d2(4 * 3, 0);
  ASSERT_TRUE(downsample_box(ConstGray8View(src.data(), 8, 6), Rect{3, 1, 4, 4}, 2,
                             Gray8View(d2.data(), 4, 3))
                  .ok());
  EXPECT_EQ(d2[0], 0);
  // Region x 3..6, y 1..4: whole blocks x 4..5 / y 2..3 only -> dst (2, 1).
  EXPECT_EQ(d2[1 * 4 + 2], (42 + 52 + 43 + 53 + 2) / 4);
  EXPECT_EQ(d2[1 * 4 + 1], 0);  // block x 2..3 is not whole in the region
}

TEST(Downsample, BadArgumentsAreNamed) {
  std::vector<std::uint8_t> src(16, 1), dst(16, 0);
  const ConstGray8View s(src.data(), 4, 4);
  EXPECT_EQ(downsample_box(s, Rect{0, 0, 4, 4}, 0, Gray8View(dst.data(), 4, 4)).code(),
            Errc::invalid_argument);
  EXPECT_EQ(downsample_box(s, Rect{2, 2, 4, 4}, 2, Gray8View(dst.data(), 4, 4)).code(),
            Errc::out_of_range);
  EXPECT_EQ(downsample_box(s, Rect{0, 0, 4, 4}, 1, Gray8View(dst.data(), 2, 2)).code(),
            Errc::out_of_range);
}

}  // namespace
}  // namespace petra
