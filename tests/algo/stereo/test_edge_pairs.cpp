#include "algo/stereo/edge_pairs.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "algo/stereo/canny.hpp"
#include "tests/algo/stereo/stereo_scene.hpp"

namespace petra::match {
namespace {

TEST(EdgePairs, IdenticalWindowsCorrelatePerfectlyAndFlatOnesNotAtAll) {
  const auto s = petra::test::make_scene(60, 20, 0.0);
  EXPECT_EQ(zncc_q10(s.lv(), 30, s.rv(), 30, 10), kZnccOne);
  std::vector<std::uint8_t> flat(60 * 20, 99);
  EXPECT_EQ(zncc_q10(ConstGray8View(flat.data(), 60, 20), 30, s.rv(), 30, 10), 0);
}

// zncc_q10 against the formula with 64-bit integer division (its quotient is
// taken in double, which must truncate to the same integer), on random and
// near-flat textures, including the borders where the window is clamped.
TEST(EdgePairs, ZnccEqualsTheIntegerFormula) {
  const int w = 64, h = 12, n = 25;
  std::mt19937 rng(3);
  long nonzero = 0;
  for (int trial = 0; trial < 40; ++trial) {
    const int spread = trial % 4 == 0 ? 3 : 256;  // some windows near the variance floor
    std::vector<std::uint8_t> a(static_cast<std::size_t>(w) * h), b(a.size());
    for (auto& v : a) v = static_cast<std::uint8_t>(rng() % spread);
    for (auto& v : b) v = static_cast<std::uint8_t>(rng() % spread);
    const ConstGray8View va(a.data(), w, h), vb(b.data(), w, h);
    auto px = [&](const ConstGray8View& v, int x, int y) {
      return static_cast<long>(v(std::clamp(x, 0, w - 1), std::clamp(y, 0, h - 1)));
    };
    for (int y = 0; y < h; ++y)
      for (int xl = 0; xl < w; xl += 3) {
        const int xr = static_cast<int>(rng() % w);
        long sa = 0, sb = 0, qa = 0, qb = 0, cross = 0;
        for (int dy = -2; dy <= 2; ++dy)
          for (int dx = -2; dx <= 2; ++dx) {
            const long p = px(va, xl + dx, y + dy), q = px(vb, xr + dx, y + dy);
            sa += p;
            sb += q;
            qa += p * p;
            qb += q * q;
            cross += p * q;
          }
        const long var_a = n * qa - sa * sa, var_b = n * qb - sb * sb;
        const long floor = static_cast<long>(n) * n * 9 / 4;
        long expect = 0;
        if (var_a >= floor && var_b >= floor) {
          const double v =
              std::sqrt(static_cast<double>(var_a)) * std::sqrt(static_cast<double>(var_b));
          const long den = std::lround(v);
          if (den > 0) expect = (n * cross - sa * sb) * kZnccOne / den;
        }
        ASSERT_EQ(zncc_q10(va, xl, vb, xr, y), expect) << trial << " " << xl << " " << y;
        nonzero += expect != 0;
      }
  }
  EXPECT_GT(nonzero, 1000);
}

TEST(EdgePairs, PairsFollowTheShiftInOrderWithinTheRange) {
  const int w = 200, h = 40, shift = 9;
  const auto s = petra::test::make_scene(w, h, shift, 0, 0, 0, 0, 0, 4);
  std::vector<std::byte> scratch(canny_scratch_bytes(w, h) + 4 * edge_row_scratch_bytes(w, w));
  Arena arena(scratch);
  std::vector<std::uint8_t> el(static_cast<std::size_t>(w) * h), er(el.size());
  ASSERT_TRUE(canny(s.lv(), {0, 0, w, h}, {}, arena, Gray8View(el.data(), w, h)).ok());
  ASSERT_TRUE(canny(s.rv(), {0, 0, w, h}, {}, arena, Gray8View(er.data(), w, h)).ok());
  std::vector<EdgePair> pairs(w);
  long total = 0, exact = 0;
  for (int y = 5; y < h - 5; ++y) {
    EdgeRowInputs in;
    in.left = s.lv();
    in.right = s.rv();
    in.y = y;
    in.left_edges = el.data() + static_cast<std::size_t>(y) * w;
    in.left_n = w;
    in.right_edges = er.data() + static_cast<std::size_t>(y) * w;
    in.right_n = w;
    in.disp_min = 0;
    in.disp_max = 20;
    in.zncc_floor_q10 = 800;
    auto n = match_edge_row(in, arena, pairs);
    ASSERT_TRUE(n.ok()) << n.error().message;
    EXPECT_EQ(arena.used(), 0u);
    for (int i = 0; i < *n; ++i) {
      const EdgePair& p = pairs[static_cast<std::size_t>(i)];
      const int d = p.x_left - p.x_right;
      EXPECT_GE(d, 0);
      EXPECT_LE(d, 20);
      EXPECT_GE(p.zncc_q10, 800);
      if (i > 0) {  // the ordering constraint
        EXPECT_GT(p.x_left, pairs[static_cast<std::size_t>(i - 1)].x_left);
        EXPECT_GT(p.x_right, pairs[static_cast<std::size_t>(i - 1)].x_right);
      }
      if (p.x_left > 25) {  // away from the border where the texture is clamped
        ++total;
        exact += std::abs(d - shift) <= 1;
      }
    }
  }
  EXPECT_GT(total, 200);
  EXPECT_GT(static_cast<double>(exact) / static_cast<double>(total), 0.95);
}

TEST(EdgePairs, TooSmallPairBufferIsAnError) {
  const int w = 120, h = 20;
  const auto s = petra::test::make_scene(w, h, 5.0);
  std::vector<std::byte> scratch(canny_scratch_bytes(w, h) + edge_row_scratch_bytes(w, w));
  Arena arena(scratch);
  std::vector<std::uint8_t> el(static_cast<std::size_t>(w) * h), er(el.size());
  ASSERT_TRUE(canny(s.lv(), {0, 0, w, h}, {}, arena, Gray8View(el.data(), w, h)).ok());
  ASSERT_TRUE(canny(s.rv(), {0, 0, w, h}, {}, arena, Gray8View(er.data(), w, h)).ok());
  EdgeRowInputs in;
  in.left = s.lv();
  in.right = s.rv();
  in.y = 10;
  in.left_edges = el.data() + 10 * w;
  in.left_n = w;
  in.right_edges = er.data() + 10 * w;
  in.right_n = w;
  in.disp_max = 10;
  std::vector<EdgePair> one(1);
  auto n = match_edge_row(in, arena, one);
  ASSERT_FALSE(n.ok());
  EXPECT_EQ(n.code(), Errc::capacity_exceeded);
}

}  // namespace
}  // namespace petra::match
