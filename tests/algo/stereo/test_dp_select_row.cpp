#include "algo/stereo/dp_select_row.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <random>
#include <vector>

#include "algo/core/disparity.hpp"

namespace petra::match {
namespace {

// The per-pixel checks written the plain way (integer divisions, branches),
// as match_dp had them before select_row: the reference for bit-identity.
struct Reference {
  std::int16_t out;
  std::uint8_t conf;
  std::uint8_t why;
};

Reference reference_selection(const SelectRowInputs& in, int i) {
  const int k1 = in.k1[i];
  const int d = in.disp_min + k1;
  const int x = in.x0 + i;
  const int b = in.best[i], s2 = in.second[i];
  const std::int16_t* s = in.S + static_cast<std::size_t>(i) * in.s_stride;
  const bool left = in.left_shadow[i] == 0;
  const bool in_range = x - d >= 0 && x - d < in.image_width;
  const bool lr = std::abs(in.right_lane[in.w - 1 - i + k1] - k1) <= in.lr_tolerance_px;
  const bool unique = static_cast<long>(s2 - b) * 100 >= static_cast<long>(in.uniqueness_pct) * s2;
  const bool cheap = in.cost[static_cast<std::size_t>(i) * in.c_stride + k1] <= in.cost_ceiling;
  const bool lit = !in_range || in.right_shadow[i + in.lanes - 1 - k1] == 0;
  const std::uint8_t why = !left       ? kShadowLeft
                           : !in_range ? kRange
                           : !lr       ? kLeftRight
                           : !unique   ? kUniqueness
                           : !cheap    ? kCost
                           : !lit      ? kShadowRight
                                       : kMatched;
  const int sa = s[k1 - 1], sb = s[k1], sc = s[k1 + 1];
  const int den = sa + sc - 2 * sb;
  const bool fit = k1 > in.lo[i] && k1 < in.hi[i] && den > 0;
  int q = d * kDisparityScale;
  if (fit) {
    const int num = 8 * (sa - sc);
    const int off = (num >= 0 ? num + den / 2 : num - den / 2) / den;
    q += std::clamp(off, -8, 8);
  }
  const bool valid = why == kMatched;
  const int margin = 255 * (s2 - b) / std::max(s2, 1);
  return Reference{valid ? static_cast<std::int16_t>(q) : kInvalidDisparity,
                   valid ? static_cast<std::uint8_t>(std::clamp(margin, 1, 255)) : std::uint8_t{0},
                   why};
}

// Random rows over the whole value ranges (path costs up to the int16
// ceiling, both signs of the parabola's numerator, every check failing
// somewhere), compared pixel by pixel with the reference.
TEST(SelectRow, MatchesThePlainIntegerChecksBitForBit) {
  std::mt19937 rng(7);
  const int w = 97, lanes = 42, stride = 64 + 16;
  long compared = 0, matched = 0, fitted_negative = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const bool big = trial % 3 == 0;  // path costs near the int16 ceiling
    std::uniform_int_distribution<int> cost_of(0, big ? 32000 : 3000);
    std::vector<std::int16_t> S(static_cast<std::size_t>(w) * stride);
    for (auto& v : S) v = static_cast<std::int16_t>(cost_of(rng));
    std::vector<std::int16_t> k1(w), best(w), second(w), lo(w), hi(w);
    std::vector<std::uint16_t> cost(static_cast<std::size_t>(w) * 64);
    for (auto& v : cost) v = static_cast<std::uint16_t>(rng() % 2000);
    std::vector<std::int16_t> right(static_cast<std::size_t>(w + lanes));
    for (auto& v : right) v = static_cast<std::int16_t>(static_cast<int>(rng() % (lanes + 1)) - 1);
    std::vector<std::uint8_t> lshadow(w), rshadow(static_cast<std::size_t>(w + lanes - 1));
    for (auto& v : lshadow) v = rng() % 10 == 0;
    for (auto& v : rshadow) v = rng() % 10 == 0;
    for (int i = 0; i < w; ++i) {
      const int k = static_cast<int>(rng() % lanes);
      k1[i] = static_cast<std::int16_t>(k);
      std::int16_t* s = S.data() + static_cast<std::size_t>(i) * stride + 8;
      best[i] = static_cast<std::int16_t>(std::min<int>(s[k], cost_of(rng) / 4));
      s[k] = best[i];  // the winner is the smallest
      second[i] = static_cast<std::int16_t>(std::max<int>(best[i], cost_of(rng)));
      if (trial % 7 == 0) second[i] = 0;  // the max(second, 1) corner
      if (rng() % 5 != 0)                 // mostly consistent right-view winners
        right[static_cast<std::size_t>(w - 1 - i + k)] =
            static_cast<std::int16_t>(k + static_cast<int>(rng() % 5) - 2);
      lo[i] = static_cast<std::int16_t>(std::max(0, k - static_cast<int>(rng() % 4)));
      hi[i] = static_cast<std::int16_t>(std::min(lanes - 1, k + static_cast<int>(rng() % 4)));
    }
    SelectRowInputs in;
    in.w = w;
    in.k1 = k1.data();
    in.best = best.data();
    in.second = second.data();
    in.S = S.data() + 8;
    in.s_stride = stride;
    in.cost = cost.data();
    in.c_stride = 64;
    in.lo = lo.data();
    in.hi = hi.data();
    in.right_lane = right.data();
    in.left_shadow = lshadow.data();
    in.right_shadow = rshadow.data();
    in.lanes = lanes;
    in.x0 = static_cast<int>(rng() % 60);
    in.disp_min = static_cast<int>(rng() % 40) - 10;
    in.image_width = 180;
    in.lr_tolerance_px = static_cast<int>(rng() % 3);
    in.uniqueness_pct = static_cast<int>(rng() % 30);
    in.cost_ceiling = trial % 5 == 0 ? (1L << 40) : static_cast<long>(rng() % 2000);
    std::vector<std::int32_t> g(5 * static_cast<std::size_t>(w));
    SelectRowScratch sc{g.data(), g.data() + w, g.data() + 2 * w, g.data() + 3 * w,
                        g.data() + 4 * w};
    std::vector<std::int16_t> out(w), out2(w);
    std::vector<std::uint8_t> conf(w), why(w), why2(w);
    const RejectCounts rc = select_row(in, sc, out.data(), conf.data(), why.data());
    select_row(in, sc, out2.data(), nullptr, why2.data());
    RejectCounts expect;
    for (int i = 0; i < w; ++i) {
      const Reference r = reference_selection(in, i);
      ASSERT_EQ(out[i], r.out) << "trial " << trial << " pixel " << i;
      ASSERT_EQ(out2[i], r.out) << "trial " << trial << " pixel " << i;
      ASSERT_EQ(conf[i], r.conf) << "trial " << trial << " pixel " << i;
      ASSERT_EQ(why[i], r.why) << "trial " << trial << " pixel " << i;
      ASSERT_EQ(why2[i], r.why);
      expect.range += r.why == kRange;
      expect.lr += r.why == kLeftRight;
      expect.uniqueness += r.why == kUniqueness;
      expect.cost += r.why == kCost;
      expect.shadow_right += r.why == kShadowRight;
      ++compared;
      matched += r.why == kMatched;
      const std::int16_t* s = in.S + static_cast<std::size_t>(i) * stride;
      fitted_negative += r.why == kMatched && s[k1[i] - 1] < s[k1[i] + 1];
    }
    EXPECT_EQ(rc.range, expect.range);
    EXPECT_EQ(rc.lr, expect.lr);
    EXPECT_EQ(rc.uniqueness, expect.uniqueness);
    EXPECT_EQ(rc.cost, expect.cost);
    EXPECT_EQ(rc.shadow_right, expect.shadow_right);
  }
  // The comparison covered accepted pixels and both parabola directions.
  EXPECT_GT(matched, compared / 10);
  EXPECT_GT(fitted_negative, 100);
}

}  // namespace
}  // namespace petra::match
