#include "algo/stereo/shadow.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <vector>

#include "tests/support/heap_counter.hpp"
#include "tests/support/owned_gray_image.hpp"

namespace petra {
namespace {

using Image = test::OwnedGray8;

// Pixel values 0..99, each once, in a 10x10 ROI inside a brighter image.
Image ramp() {
  Image img(20, 20, 200);
  for (int i = 0; i < 100; ++i)
    img.view()(5 + i % 10, 5 + i / 10) = static_cast<std::uint8_t>((i * 37) % 100);
  return img;
}

TEST(Shadow, ThresholdIsWhereTheCumulativeHistogramReachesP) {
  Image img = ramp();
  auto t = shadow_threshold(img.view(), {5, 5, 10, 10}, 0.2);
  ASSERT_TRUE(t.ok()) << t.error().message;
  EXPECT_EQ(t->threshold, 19);  // values 0..19 are the darkest 20 %
  EXPECT_EQ(t->shadow_pixels, 20);
  EXPECT_EQ(t->roi_pixels, 100);
  auto t2 = shadow_threshold(img.view(), {5, 5, 10, 10}, 0.205);  // ceil(20.5) = 21 pixels
  ASSERT_TRUE(t2.ok());
  EXPECT_EQ(t2->threshold, 20);
}

TEST(Shadow, ZeroFractionMarksNothing) {
  Image img = ramp();
  auto t = shadow_threshold(img.view(), {5, 5, 10, 10}, 0.0);
  ASSERT_TRUE(t.ok());
  EXPECT_EQ(t->threshold, -1);
  std::vector<std::uint8_t> m(100, 7);
  auto n = shadow_mask(img.view(), {5, 5, 10, 10}, t->threshold, Gray8View(m.data(), 10, 10));
  ASSERT_TRUE(n.ok());
  EXPECT_EQ(*n, 0);
  for (std::uint8_t v : m) EXPECT_EQ(v, 0);
}

TEST(Shadow, MaskMarksExactlyThePixelsAtOrBelowTheThreshold) {
  Image img = ramp();
  std::vector<std::uint8_t> m(100);
  auto n = shadow_mask(img.view(), {5, 5, 10, 10}, 19, Gray8View(m.data(), 10, 10));
  ASSERT_TRUE(n.ok());
  EXPECT_EQ(*n, 20);
  for (int y = 0; y < 10; ++y)
    for (int x = 0; x < 10; ++x)
      EXPECT_EQ(m[y * 10 + x] != 0, img.view()(5 + x, 5 + y) <= 19) << x << "," << y;
  ShadowMask sm{ImageView<const std::uint8_t>(m.data(), 10, 10), {5, 5, 10, 10}};
  EXPECT_FALSE(sm.is_shadow(0, 0));  // outside the area: lit
  for (int y = 0; y < 10; ++y)
    for (int x = 0; x < 10; ++x)
      EXPECT_EQ(sm.is_shadow(5 + x, 5 + y), img.view()(5 + x, 5 + y) <= 19);
}

TEST(Shadow, LeftAndRightThresholdsAreIndependent) {
  // Same scene, the right view's shadow is larger and a little lighter.
  Image l(40, 40, 150), r(40, 40, 150);
  for (int y = 0; y < 40; ++y)
    for (int x = 0; x < 40; ++x) {
      if (y >= 30) l.view()(x, y) = 30;  // 25 % shadow at gray 30
      if (y >= 26) r.view()(x, y) = 45;  // 35 % shadow at gray 45
    }
  auto tl = shadow_threshold(l.view(), {0, 0, 40, 40}, 0.25);
  auto tr = shadow_threshold(r.view(), {0, 0, 40, 40}, 0.25);
  ASSERT_TRUE(tl.ok() && tr.ok());
  EXPECT_EQ(tl->threshold, 30);
  EXPECT_EQ(tr->threshold, 45);
  EXPECT_EQ(tl->shadow_pixels, 400);
  EXPECT_EQ(tr->shadow_pixels, 560);
}

TEST(Shadow, AllShadowRoiIsAnError) {
  Image img(30, 30, 12);
  auto t = shadow_threshold(img.view(), {0, 0, 30, 30}, 0.1);
  ASSERT_FALSE(t.ok());
  EXPECT_EQ(t.code(), Errc::degenerate);
  EXPECT_NE(std::strstr(t.error().message, "all shadow"), nullptr) << t.error().message;
}

TEST(Shadow, BadInputNamesTheProblem) {
  Image img = ramp();
  auto a = shadow_threshold(img.view(), {15, 15, 10, 10}, 0.1);
  EXPECT_EQ(a.code(), Errc::out_of_range);
  EXPECT_NE(std::strstr(a.error().message, "outside"), nullptr);
  auto b = shadow_threshold(img.view(), {0, 0, 0, 5}, 0.1);
  EXPECT_EQ(b.code(), Errc::invalid_argument);
  EXPECT_NE(std::strstr(b.error().message, "empty"), nullptr);
  for (double p : {-0.1, 1.0, 2.0, std::nan("")}) {
    auto c = shadow_threshold(img.view(), {0, 0, 10, 10}, p);
    EXPECT_EQ(c.code(), Errc::invalid_argument) << p;
    EXPECT_NE(std::strstr(c.error().message, "fraction"), nullptr);
  }
  std::vector<std::uint8_t> m(50);
  auto d = shadow_mask(img.view(), {0, 0, 10, 10}, 10, Gray8View(m.data(), 5, 10));
  EXPECT_EQ(d.code(), Errc::invalid_argument);
  EXPECT_NE(std::strstr(d.error().message, "mask"), nullptr);
}

TEST(Shadow, RandomImagesMaskAtLeastPAndOnlyTheDarkest) {
  std::mt19937 rng(5);
  std::uniform_int_distribution<int> g(0, 255);
  for (int trial = 0; trial < 20; ++trial) {
    Image img(64, 48);
    for (auto& v : img.px) v = static_cast<std::uint8_t>(g(rng));
    const double p = 0.05 * (trial % 10 + 1);
    const Rect roi{3, 2, 50, 40};
    auto t = shadow_threshold(img.view(), roi, p);
    ASSERT_TRUE(t.ok());
    std::vector<std::uint8_t> m(static_cast<std::size_t>(roi.area()));
    auto n = shadow_mask(img.view(), roi, t->threshold, Gray8View(m.data(), roi.w, roi.h));
    ASSERT_TRUE(n.ok());
    EXPECT_EQ(*n, t->shadow_pixels);
    EXPECT_GE(static_cast<double>(*n), p * static_cast<double>(roi.area()));
    int max_shadow = -1, min_lit = 256;
    for (int y = 0; y < roi.h; ++y)
      for (int x = 0; x < roi.w; ++x) {
        const int v = img.view()(roi.x + x, roi.y + y);
        if (m[static_cast<std::size_t>(y * roi.w + x)])
          max_shadow = std::max(max_shadow, v);
        else
          min_lit = std::min(min_lit, v);
      }
    EXPECT_LT(max_shadow, min_lit);  // shadow is darker than everything lit
  }
}

// The right view's windows of a 100 px ROI at x = 300 of a 640 px image,
// matched over 10..50 px: the histogram window is the ROI shifted by the
// middle disparity (30), the mask the columns 250..389 the range reaches.
TEST(Shadow, RightWindowsAreTheMiddleDisparityAndTheSearchArea) {
  const Rect roi{300, 40, 100, 80};
  const RightShadowWindows w = right_shadow_windows(roi, 10, 50, 640);
  EXPECT_EQ(w.histogram.x, 270);
  EXPECT_EQ(w.histogram.y, 40);
  EXPECT_EQ(w.histogram.w, 100);
  EXPECT_EQ(w.histogram.h, 80);
  EXPECT_EQ(w.mask.x, 250);
  EXPECT_EQ(w.mask.w, 140);
  EXPECT_EQ(w.mask.h, 80);
  // Near the left edge the histogram window is clamped into the image.
  EXPECT_EQ(right_shadow_windows({10, 0, 100, 80}, 10, 50, 640).histogram.x, 0);
  // A range that reaches no column: an empty mask area.
  EXPECT_TRUE(right_shadow_windows({0, 0, 20, 10}, 30, 40, 640).mask.empty());
}

TEST(Shadow, AllocatesNothing) {
  Image img = ramp();
  std::vector<std::uint8_t> m(100);
  petra::test::HeapScope scope;
  for (int i = 0; i < 10; ++i) {
    auto t = shadow_threshold(img.view(), {5, 5, 10, 10}, 0.3);
    ASSERT_TRUE(t.ok());
    auto n = shadow_mask(img.view(), {5, 5, 10, 10}, t->threshold, Gray8View(m.data(), 10, 10));
    ASSERT_TRUE(n.ok());
  }
  EXPECT_EQ(scope.allocations(), 0u);
}

}  // namespace
}  // namespace petra
