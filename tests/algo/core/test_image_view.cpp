#include "algo/core/image_view.hpp"

#include <gtest/gtest.h>

#include <array>

namespace petra {
namespace {

TEST(ImageView, SubViewSharesMemoryWithStride) {
  std::array<std::uint8_t, 6 * 4> pixels{};
  auto img = Gray8View::over(pixels, 6, 4);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 6; ++x) img(x, y) = static_cast<std::uint8_t>(10 * y + x);
  auto roi = img.sub({2, 1, 3, 2});
  EXPECT_EQ(roi.width(), 3);
  EXPECT_EQ(roi.stride(), 6);
  EXPECT_EQ(roi(0, 0), 12);
  EXPECT_EQ(roi(2, 1), 24);
  roi(1, 1) = 200;
  EXPECT_EQ(img(3, 2), 200);
  ConstGray8View ro = roi;
  EXPECT_EQ(ro(1, 1), 200);
}

TEST(Rect, InsideAndContains) {
  const Rect r{10, 20, 30, 40};
  EXPECT_TRUE(r.inside(40, 60));
  EXPECT_FALSE(r.inside(39, 60));
  EXPECT_FALSE((Rect{-1, 0, 5, 5}).inside(100, 100));
  EXPECT_TRUE(r.contains(10, 20));
  EXPECT_FALSE(r.contains(40, 20));
  EXPECT_TRUE((Rect{0, 0, 0, 5}).empty());
  EXPECT_EQ(r.area(), 1200);
}

TEST(ImageView, CopyPixelsConverts) {
  std::array<std::uint8_t, 4> a{1, 2, 3, 4};
  std::array<float, 4> b{};
  copy_pixels<std::uint8_t, float>(ConstGray8View::over(std::span<const std::uint8_t>(a), 2, 2),
                                   ImageView<float>::over(b, 2, 2));
  EXPECT_FLOAT_EQ(b[3], 4.0f);
}

}  // namespace
}  // namespace petra
