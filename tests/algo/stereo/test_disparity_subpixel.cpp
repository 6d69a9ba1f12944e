// Sub-pixel refinement of whole-pixel disparities (algo/stereo/disparity_subpixel):
// a textured right view made from the left by a known fractional shift.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "algo/stereo/disparity_subpixel.hpp"
#include "tests/support/heap_counter.hpp"

namespace petra {
namespace {

constexpr int kW = 120, kH = 40;

// A smooth texture (sum of sines) so linear sampling is close to the truth.
double texture(double x, double y) {
  return 128 + 50 * std::sin(0.7 * x + 0.3 * y) + 40 * std::sin(0.31 * x - 0.5 * y + 1.0) +
         20 * std::cos(1.3 * x + 0.9 * y);
}

struct ShiftedPair {
  std::vector<std::uint8_t> left, right;
  explicit ShiftedPair(double shift_px) : left(kW * kH), right(kW * kH) {
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) {
        left[y * kW + x] = static_cast<std::uint8_t>(std::lround(texture(x, y)));
        // Right pixel x sees left pixel x + shift (d = x_left - x_right).
        right[y * kW + x] = static_cast<std::uint8_t>(std::lround(texture(x + shift_px, y)));
      }
  }
  StereoInput input() const {
    StereoInput in;
    in.left = ConstGray8View(left.data(), kW, kH);
    in.right = ConstGray8View(right.data(), kW, kH);
    return in;
  }
};

TEST(DisparitySubpixel, MovesWholePixelLabelsTowardsTheTrueShift) {
  for (double shift : {6.25, 6.5, 6.8, 7.0}) {
    const ShiftedPair p(shift);
    const Rect roi{20, 5, 80, 30};
    std::vector<std::int16_t> q4(roi.w * roi.h, disparity_q4(std::round(shift)));
    q4[0] = kInvalidDisparity;  // invalid pixels stay invalid
    DisparityMap map{ImageView<std::int16_t>(q4.data(), roi.w, roi.h), roi};
    test::HeapScope scope;
    auto n = refine_subpixel(p.input(), {}, map);
    EXPECT_EQ(scope.allocations(), 0u);
    ASSERT_TRUE(n.ok()) << n.error().message;
    EXPECT_GT(*n, roi.w * roi.h * 9 / 10) << shift;
    EXPECT_EQ(q4[0], kInvalidDisparity);
    double sum = 0;
    long count = 0;
    for (std::int16_t v : q4)
      if (is_valid_disparity(v)) {
        sum += std::abs(disparity_px(v) - shift);
        ++count;
      }
    // Whole pixels are up to 0.5 px off; the parabola brings the mean error
    // under 0.15 px (its known bias towards whole pixels remains).
    EXPECT_LT(sum / static_cast<double>(count), 0.15) << shift;
  }
}

TEST(DisparitySubpixel, LabelsUpToSearchPxOffAreCorrected) {
  const ShiftedPair p(6.3);
  const Rect roi{20, 5, 80, 30};
  for (int off : {-2, 2}) {
    std::vector<std::int16_t> q4(roi.w * roi.h, disparity_q4(6 + off));
    DisparityMap map{ImageView<std::int16_t>(q4.data(), roi.w, roi.h), roi};
    SubpixelParams narrow;
    narrow.search_px = 1;  // from 4 or 8 it reaches 5 or 7 at best
    std::vector<std::int16_t> copy = q4;
    DisparityMap map1{ImageView<std::int16_t>(copy.data(), roi.w, roi.h), roi};
    ASSERT_TRUE(refine_subpixel(p.input(), narrow, map1).ok());
    ASSERT_TRUE(refine_subpixel(p.input(), {}, map).ok());  // search_px 2
    double err = 0, err1 = 0;
    for (std::size_t i = 0; i < q4.size(); ++i) {
      err += std::abs(disparity_px(q4[i]) - 6.3);
      err1 += std::abs(disparity_px(copy[i]) - 6.3);
    }
    const double n = static_cast<double>(q4.size());
    EXPECT_LT(err / n, 0.15) << off;
    EXPECT_GT(err1 / n, 0.5) << off;
  }
}

TEST(DisparitySubpixel, WindowsOutsideTheImageKeepTheirValue) {
  const ShiftedPair p(3.0);
  const Rect roi{0, 0, 6, kH};  // right windows at x - d leave the image
  std::vector<std::int16_t> q4(roi.w * roi.h, disparity_q4(3.0));
  DisparityMap map{ImageView<std::int16_t>(q4.data(), roi.w, roi.h), roi};
  auto n = refine_subpixel(p.input(), {}, map);
  ASSERT_TRUE(n.ok());
  EXPECT_EQ(*n, 0);
  for (std::int16_t v : q4) EXPECT_EQ(v, disparity_q4(3.0));
}

TEST(DisparitySubpixel, BadInputIsNamed) {
  const ShiftedPair p(3.0);
  std::vector<std::int16_t> q4(10 * 10, 0);
  DisparityMap map{ImageView<std::int16_t>(q4.data(), 10, 10), Rect{kW - 5, 0, 10, 10}};
  auto n = refine_subpixel(p.input(), {}, map);
  EXPECT_NE(std::string(n.error().message).find("ROI"), std::string::npos);
  map.roi = Rect{0, 0, 10, 10};
  SubpixelParams bad;
  bad.window_radius = 0;
  EXPECT_NE(std::string(refine_subpixel(p.input(), bad, map).error().message).find("window_radius"),
            std::string::npos);
  SubpixelParams far;
  far.search_px = kMaxSearchPx + 1;
  EXPECT_NE(std::string(refine_subpixel(p.input(), far, map).error().message).find("search_px"),
            std::string::npos);
}

}  // namespace
}  // namespace petra
