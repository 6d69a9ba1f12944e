// Disparity and shadow-mask scores on small hand-made images.
#include "sim/score/image_score.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace petra::sim {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

TEST(ImageScore, DisparityBadPixelsCoverageAndError) {
  io::FloatImage truth(4, 2, 10.0f), out(4, 2, 10.0f);
  truth.view()(3, 1) = kInf;  // no truth: not counted
  out.view()(0, 0) = 10.5f;   // good
  out.view()(1, 0) = 11.5f;   // bad-1 only
  out.view()(2, 0) = 7.0f;    // bad-1 and bad-2
  out.view()(3, 0) = kInf;    // invalid: bad
  out.view()(3, 1) = 99.0f;   // no truth here
  auto s = score_disparity(out, truth, {0, 0, 4, 2});
  ASSERT_TRUE(s.ok()) << s.error().message;
  EXPECT_EQ(s->truth_pixels, 7);
  EXPECT_EQ(s->valid_pixels, 6);
  EXPECT_NEAR(s->bad1_pct, 100.0 * 3 / 7, 1e-9);
  EXPECT_NEAR(s->bad2_pct, 100.0 * 2 / 7, 1e-9);
  EXPECT_NEAR(s->coverage_pct, 100.0 * 6 / 7, 1e-9);
  EXPECT_NEAR(s->bad1_valid_pct, 100.0 * 2 / 6, 1e-9);
  EXPECT_NEAR(s->mean_abs_error_px, (0.5 + 1.5 + 3.0) / 6, 1e-6);
  // A region restricts the count.
  auto r = score_disparity(out, truth, {0, 0, 2, 1});
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r->truth_pixels, 2);
  EXPECT_NEAR(r->bad1_pct, 50.0, 1e-9);
}

TEST(ImageScore, DisparityInputsMustAgree) {
  io::FloatImage a(4, 2), b(5, 2);
  EXPECT_FALSE(score_disparity(a, b, {0, 0, 4, 2}).ok());
  auto r = score_disparity(a, a, {2, 0, 4, 2});
  ASSERT_FALSE(r.ok());
  EXPECT_NE(std::string(r.error().message).find("region"), std::string::npos);
}

TEST(ImageScore, ShadowPrecisionRecallIoU) {
  io::GrayImage truth(4, 1), out(4, 1);
  truth.pixels = {255, 255, 0, 0};
  out.pixels = {255, 0, 200, 0};  // TP, FN, FP, TN (>= 128 is shadow)
  auto s = score_mask(out, truth, {0, 0, 4, 1});
  ASSERT_TRUE(s.ok());
  EXPECT_EQ(s->true_positive, 1);
  EXPECT_EQ(s->false_negative, 1);
  EXPECT_EQ(s->false_positive, 1);
  EXPECT_EQ(s->true_negative, 1);
  EXPECT_DOUBLE_EQ(s->precision, 0.5);
  EXPECT_DOUBLE_EQ(s->recall, 0.5);
  EXPECT_DOUBLE_EQ(s->iou, 1.0 / 3);
  // Nothing predicted: precision undefined, recall 0.
  io::GrayImage none(4, 1, 0);
  auto n = score_mask(none, truth, {0, 0, 4, 1});
  ASSERT_TRUE(n.ok());
  EXPECT_TRUE(std::isnan(n->precision));
  EXPECT_DOUBLE_EQ(n->recall, 0.0);
}

}  // namespace
}  // namespace petra::sim
