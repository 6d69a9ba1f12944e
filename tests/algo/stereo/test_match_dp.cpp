#include "algo/stereo/match_dp.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>

#include "tests/algo/stereo/stereo_scene.hpp"
#include "tests/support/heap_counter.hpp"

namespace petra {
namespace {

using petra::test::make_scene;
using petra::test::make_tilted_scene;
using petra::test::StereoScene;

// Caller-side memory of one matcher, sized at "init" for a budget.
struct DpMatcherUnderTest {
  MatchBudget budget;
  std::vector<std::byte> scratch;
  Arena arena;
  std::vector<std::int16_t> q4;
  std::vector<std::uint8_t> conf;

  explicit DpMatcherUnderTest(MatchBudget b)
      : budget(b),
        scratch(match_dp_scratch_bytes(b)),
        arena(scratch),
        q4(static_cast<std::size_t>(b.max_width) * b.max_height),
        conf(q4.size()) {}

  Result<MatchDpStats> run(const StereoScene& s, Rect roi, MatchDpParams p, DisparityMap& out,
                           const ShadowMask* ls = nullptr, const ShadowMask* rs = nullptr) {
    out = DisparityMap{ImageView<std::int16_t>(q4.data(), roi.w, roi.h), {}};
    StereoInput in{s.lv(), s.rv(), ls, rs};
    return match_dp(in, roi, p, budget, arena, out,
                    ImageView<std::uint8_t>(conf.data(), roi.w, roi.h));
  }
};

MatchDpParams range(int lo, int hi) {
  MatchDpParams p;
  p.disp_min = lo;
  p.disp_max = hi;
  return p;
}

struct Accuracy {
  double coverage = 0;    // valid / pixels with a visible truth
  double within_1px = 0;  // of valid pixels with truth
  double mean_abs = 0;    // px, of valid pixels with truth
};

Accuracy accuracy(const StereoScene& s, const DisparityMap& m) {
  long visible = 0, valid = 0, good = 0;
  double err = 0;
  for (int y = 0; y < m.roi.h; ++y)
    for (int x = 0; x < m.roi.w; ++x) {
      const float t = s.d(m.roi.x + x, m.roi.y + y);
      if (std::isnan(t)) continue;
      ++visible;
      const std::int16_t q = m.q4(x, y);
      if (!is_valid_disparity(q)) continue;
      ++valid;
      const double e = std::fabs(disparity_px(q) - static_cast<double>(t));
      good += e <= 1.0;
      err += e;
    }
  Accuracy a;
  a.coverage = visible ? static_cast<double>(valid) / static_cast<double>(visible) : 0;
  a.within_1px = valid ? static_cast<double>(good) / static_cast<double>(valid) : 0;
  a.mean_abs = valid ? err / static_cast<double>(valid) : 0;
  return a;
}

TEST(MatchDp, RecoversAConstantIntegerDisparity) {
  const StereoScene s = make_scene(160, 100, 7.0);
  DpMatcherUnderTest m({120, 80, 32});
  DisparityMap out;
  auto st = m.run(s, {30, 10, 120, 80}, range(0, 20), out);
  ASSERT_TRUE(st.ok()) << st.error().message;
  const Accuracy a = accuracy(s, out);
  EXPECT_GT(a.coverage, 0.97);
  EXPECT_GT(a.within_1px, 0.999);
  EXPECT_LT(a.mean_abs, 0.1);
  EXPECT_EQ(out.roi, (Rect{30, 10, 120, 80}));
  EXPECT_GT(st->anchors, 100);
}

// A face turned up to the sky: its disparity grows by half a pixel per row, so
// the upright 5x9 box spans 4 px of disparity; the slanted box follows it.
TEST(MatchDp, SlantedBoxFollowsAFaceTurnedUp) {
  const StereoScene s = make_tilted_scene(200, 120, 8.0, 0.5);
  DpMatcherUnderTest m({160, 100, 80});
  const Rect roi{20, 10, 160, 100};
  MatchDpParams p = range(0, 79);
  Accuracy with[2];
  for (bool slanted : {false, true}) {
    p.slanted_window = slanted;
    DisparityMap out;
    ASSERT_TRUE(m.run(s, roi, p, out).ok());
    with[slanted] = accuracy(s, out);
    std::printf("slanted box %s: coverage %.3f, within 1 px %.3f, mean |error| %.3f px\n",
                slanted ? "on " : "off", with[slanted].coverage, with[slanted].within_1px,
                with[slanted].mean_abs);
  }
  EXPECT_LT(with[true].mean_abs, 0.5 * with[false].mean_abs);
  EXPECT_GT(with[true].within_1px, 0.95);
  EXPECT_GT(with[true].coverage, 2 * with[false].coverage);
}

TEST(MatchDp, RefinesASubPixelDisparity) {
  const StereoScene s = make_scene(160, 100, 5.5);
  DpMatcherUnderTest m({120, 80, 32});
  DisparityMap out;
  ASSERT_TRUE(m.run(s, {30, 10, 120, 80}, range(0, 15), out).ok());
  const Accuracy a = accuracy(s, out);
  EXPECT_GT(a.coverage, 0.9);
  EXPECT_LT(a.mean_abs, 0.25);  // integer matching alone would be 0.5 off
}

TEST(MatchDp, NegativeDisparitiesAsInThePaper) {
  const StereoScene s = make_scene(160, 100, -6.0);  // paper: range -21..20
  DpMatcherUnderTest m({120, 80, 42});
  DisparityMap out;
  ASSERT_TRUE(m.run(s, {20, 10, 120, 80}, range(-21, 20), out).ok());
  const Accuracy a = accuracy(s, out);
  EXPECT_GT(a.coverage, 0.95);
  EXPECT_GT(a.within_1px, 0.99);
}

TEST(MatchDp, SeparatesABoxFromTheBackgroundAndLeavesItsOcclusionInvalid) {
  const StereoScene s = make_scene(200, 120, 4.0, 14.0, 80, 30, 60, 60);
  DpMatcherUnderTest m({180, 110, 24});
  DisparityMap out;
  auto st = m.run(s, {10, 5, 180, 110}, range(0, 23), out);
  ASSERT_TRUE(st.ok()) << st.error().message;
  const Accuracy a = accuracy(s, out);
  EXPECT_GT(a.coverage, 0.9);
  EXPECT_GT(a.within_1px, 0.97);
  // The background strip hidden from the right camera (left of the box).
  long occluded = 0, invalid = 0;
  for (int y = 35; y < 85; ++y)
    for (int x = 72; x < 78; ++x) {
      ++occluded;
      invalid += !is_valid_disparity(out.q4(x - 10, y - 5));
    }
  EXPECT_GT(static_cast<double>(invalid) / static_cast<double>(occluded), 0.7);
  EXPECT_GT(st->rejected_lr, 0);
}

TEST(MatchDp, EdgeConstraintKeepsTheDenseResult) {
  const StereoScene s = make_scene(200, 120, 4.0, 14.0, 80, 30, 60, 60, 3);
  DpMatcherUnderTest m({180, 110, 24});
  DisparityMap out;
  MatchDpParams p = range(0, 23);
  ASSERT_TRUE(m.run(s, {10, 5, 180, 110}, p, out).ok());
  const Accuracy with = accuracy(s, out);
  p.edge_constraint = false;
  auto st = m.run(s, {10, 5, 180, 110}, p, out);
  ASSERT_TRUE(st.ok());
  EXPECT_EQ(st->anchors, 0);
  const Accuracy without = accuracy(s, out);
  EXPECT_NEAR(with.within_1px, without.within_1px, 0.02);
  EXPECT_NEAR(with.coverage, without.coverage, 0.03);
}

TEST(MatchDp, ShadowPixelsGetNoDisparity) {
  const StereoScene s = make_scene(160, 100, 7.0);
  const Rect roi{30, 10, 120, 80};
  // Left shadow: a 30x20 block; right shadow: a 20x20 block elsewhere.
  std::vector<std::uint8_t> lm(static_cast<std::size_t>(roi.area()), 0), rm(160 * 100, 0);
  for (int y = 20; y < 40; ++y)
    for (int x = 40; x < 70; ++x) lm[static_cast<std::size_t>(y * roi.w + x)] = kShadowPixel;
  for (int y = 50; y < 70; ++y)
    for (int x = 60; x < 80; ++x) rm[static_cast<std::size_t>(y * 160 + x)] = kShadowPixel;
  ShadowMask ls{ImageView<const std::uint8_t>(lm.data(), roi.w, roi.h), roi};
  ShadowMask rs{ImageView<const std::uint8_t>(rm.data(), 160, 100), {0, 0, 160, 100}};
  DpMatcherUnderTest m({120, 80, 32});
  DisparityMap out;
  auto st = m.run(s, roi, range(0, 20), out, &ls, &rs);
  ASSERT_TRUE(st.ok()) << st.error().message;
  EXPECT_EQ(st->shadow_left, 600);
  for (int y = 0; y < roi.h; ++y)
    for (int x = 0; x < roi.w; ++x) {
      const std::int16_t q = out.q4(x, y);
      if (ls.is_shadow(roi.x + x, roi.y + y)) {
        EXPECT_FALSE(is_valid_disparity(q));
      }
      if (is_valid_disparity(q)) {
        const int xr = roi.x + x - static_cast<int>(std::lround(disparity_px(q)));
        EXPECT_FALSE(rs.is_shadow(xr, roi.y + y))
            << "match into the right shadow at " << x << "," << y;
      }
    }
  EXPECT_GT(st->rejected_shadow_right, 100);  // of the 400 pixels that match into it
  EXPECT_GT(accuracy(s, out).within_1px, 0.99);
}

TEST(MatchDp, ConfidenceIsZeroExactlyWhereInvalid) {
  const StereoScene s = make_scene(200, 120, 4.0, 14.0, 80, 30, 60, 60);
  DpMatcherUnderTest m({180, 110, 24});
  DisparityMap out;
  ASSERT_TRUE(m.run(s, {10, 5, 180, 110}, range(0, 23), out).ok());
  for (int y = 0; y < 110; ++y)
    for (int x = 0; x < 180; ++x)
      EXPECT_EQ(is_valid_disparity(out.q4(x, y)),
                m.conf[static_cast<std::size_t>(y * 180 + x)] != 0);
}

TEST(MatchDp, EveryBadInputIsAnErrorNamingTheProblem) {
  const StereoScene s = make_scene(160, 100, 7.0);
  DpMatcherUnderTest m({100, 80, 32});
  DisparityMap out;
  auto expect = [&](Result<MatchDpStats> r, Errc code, const char* words) {
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.code(), code) << r.error().message;
    EXPECT_NE(std::strstr(r.error().message, words), nullptr) << r.error().message;
  };
  expect(m.run(s, {100, 50, 100, 60}, range(0, 20), out), Errc::out_of_range, "outside");
  expect(m.run(s, {10, 10, 0, 60}, range(0, 20), out), Errc::invalid_argument, "empty");
  expect(m.run(s, {0, 0, 150, 60}, range(0, 20), out), Errc::capacity_exceeded,
         "exceeds the budget");
  expect(m.run(s, {0, 0, 50, 50}, range(0, 40), out), Errc::capacity_exceeded,
         "disparity range of 41");
  expect(m.run(s, {0, 0, 50, 50}, range(10, 5), out), Errc::invalid_argument, "is empty");
  expect(m.run(s, {0, 0, 50, 50}, range(200, 220), out), Errc::out_of_range,
         "outside the right image");
  MatchDpParams bad = range(0, 20);
  bad.p2 = 10000;
  expect(m.run(s, {0, 0, 50, 50}, bad, out), Errc::invalid_argument, "P2");
  bad = range(0, 20);
  bad.slant_penalty = -1;
  expect(m.run(s, {0, 0, 50, 50}, bad, out), Errc::invalid_argument, "slant_penalty -1");
  bad = range(0, 20);
  bad.slant_min_mean_cost = 25;
  expect(m.run(s, {0, 0, 50, 50}, bad, out), Errc::invalid_argument, "slant_min_mean_cost 25");
  // Mismatched image sizes.
  const StereoScene other = make_scene(150, 100, 7.0);
  StereoInput in{s.lv(), other.rv()};
  DisparityMap small{ImageView<std::int16_t>(m.q4.data(), 50, 50), {}};
  expect(match_dp(in, {0, 0, 50, 50}, range(0, 20), m.budget, m.arena, small),
         Errc::invalid_argument, "right is 150x100");
  // Output of the wrong size.
  StereoInput ok_in{s.lv(), s.rv()};
  expect(match_dp(ok_in, {0, 0, 60, 50}, range(0, 20), m.budget, m.arena, small),
         Errc::invalid_argument, "output is 50x50");
  // An all-shadow ROI.
  std::vector<std::uint8_t> all(50 * 50, kShadowPixel);
  ShadowMask dark{ImageView<const std::uint8_t>(all.data(), 50, 50), {0, 0, 50, 50}};
  expect(m.run(s, {0, 0, 50, 50}, range(0, 20), out, &dark), Errc::degenerate, "shadow");
  // A textureless ROI.
  StereoScene flat = s;
  std::fill(flat.left.begin(), flat.left.end(), std::uint8_t{120});
  std::fill(flat.right.begin(), flat.right.end(), std::uint8_t{120});
  expect(m.run(flat, {10, 10, 60, 60}, range(0, 20), out), Errc::degenerate, "textureless");
  // Too little scratch memory.
  std::vector<std::byte> tiny(4096);
  Arena small_arena(tiny);
  DisparityMap o2{ImageView<std::int16_t>(m.q4.data(), 50, 50), {}};
  expect(match_dp(ok_in, {0, 0, 50, 50}, range(0, 20), m.budget, small_arena, o2),
         Errc::capacity_exceeded, "arena");
}

TEST(MatchDp, RepeatedCallsAllocateNothingAndStayWithinTheStatedMemory) {
  const StereoScene s = make_scene(200, 120, 4.0, 14.0, 80, 30, 60, 60);
  DpMatcherUnderTest m({180, 110, 24});
  DisparityMap out;
  {
    petra::test::HeapScope scope;
    for (int i = 0; i < 3; ++i) {
      auto st = m.run(s, {10, 5, 180, 110}, range(0, 23), out);
      ASSERT_TRUE(st.ok());
      EXPECT_LE(st->scratch_high_water, m.scratch.size());
      EXPECT_EQ(m.arena.used(), 0u);  // everything released on return
    }
    EXPECT_EQ(scope.allocations(), 0u);
  }
  // Same input, same output (no hidden state between calls).
  std::vector<std::int16_t> first(m.q4.begin(), m.q4.begin() + 180 * 110);
  ASSERT_TRUE(m.run(s, {10, 5, 180, 110}, range(0, 23), out).ok());
  EXPECT_TRUE(std::equal(first.begin(), first.end(), m.q4.begin()));
}

TEST(MatchDp, FlightBudgetFitsItsStatedMemory) {
  // The flight default: ROI up to 320x320 px, 128 disparities.
  const MatchBudget flight{};
  const std::size_t bytes = match_dp_scratch_bytes(flight);
  EXPECT_EQ(bytes, 1841243u);  // the figure stated in match_dp.hpp and docs/matching.md
  const StereoScene s = make_scene(460, 330, 20.0, 60.0, 150, 100, 120, 120);
  DpMatcherUnderTest m(flight);
  DisparityMap out;
  auto st = m.run(s, {135, 5, 320, 320}, range(0, 127), out);
  ASSERT_TRUE(st.ok()) << st.error().message;
  EXPECT_LE(st->scratch_high_water, bytes);
  EXPECT_GT(accuracy(s, out).within_1px, 0.97);
}

}  // namespace
}  // namespace petra
