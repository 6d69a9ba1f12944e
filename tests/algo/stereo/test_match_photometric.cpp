// The right view's gray-level map (algo/stereo/match_photometric): it undoes a
// camera gain and offset, keeps equal views unchanged, and stays sane on
// flat or empty areas. The effect on matching real pairs is measured in
// tests/sim/eval/test_middlebury.cpp.
#include "algo/stereo/match_photometric.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <vector>

#include "tests/support/heap_counter.hpp"

namespace petra::match {
namespace {

// A textured test image: a smooth ramp plus a fixed pattern, 40..215.
std::vector<std::uint8_t> textured(int w, int h) {
  std::vector<std::uint8_t> px(static_cast<std::size_t>(w) * h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      px[static_cast<std::size_t>(y) * w + x] =
          static_cast<std::uint8_t>(40 + (x * 3 + y * 2) % 120 + ((x * 7 + y * 13) % 11) * 5);
  return px;
}

TEST(MatchPhotometric, EqualViewsGiveTheIdentity) {
  const int w = 64, h = 48;
  const auto px = textured(w, h);
  const ConstGray8View v(px.data(), w, h);
  const GrayMap m = right_to_left_gray_map(v, {0, 0, w, h}, v, {0, 0, w, h});
  EXPECT_EQ(m.gain_q8, 256);
  for (int g = 0; g < 256; ++g) EXPECT_EQ(m.level[g], g);
}

TEST(MatchPhotometric, UndoesAGainAndAnOffset) {
  const int w = 64, h = 48;
  const auto left = textured(w, h);
  std::vector<std::uint8_t> right(left.size());
  for (std::size_t i = 0; i < left.size(); ++i)
    right[i] = static_cast<std::uint8_t>(std::lround(0.82 * left[i] + 12.0));
  const ConstGray8View l(left.data(), w, h), r(right.data(), w, h);
  const GrayMap m = right_to_left_gray_map(l, {0, 0, w, h}, r, {0, 0, w, h});
  EXPECT_NEAR(m.gain_q8, 256 / 0.82, 3.0);
  int worst = 0;
  for (std::size_t i = 0; i < left.size(); ++i)
    worst = std::max(worst, std::abs(m(right[i]) - left[i]));
  EXPECT_LE(worst, 1);  // the right view's rounding to whole levels, amplified by 1/0.82
}

TEST(MatchPhotometric, FlatOrEmptyAreasGiveAnOffsetOrTheIdentity) {
  const int w = 16, h = 16;
  std::vector<std::uint8_t> left(static_cast<std::size_t>(w) * h, 100);
  std::vector<std::uint8_t> right(left.size(), 90);
  const ConstGray8View l(left.data(), w, h), r(right.data(), w, h);
  const GrayMap flat = right_to_left_gray_map(l, {0, 0, w, h}, r, {0, 0, w, h});
  EXPECT_EQ(flat.gain_q8, 256);
  EXPECT_EQ(flat(90), 100);
  EXPECT_EQ(flat(0), 10);
  EXPECT_EQ(flat(255), 255);                                                       // clamped
  const GrayMap none = right_to_left_gray_map(l, {0, 0, w, h}, r, {20, 0, 5, 5});  // outside
  for (int g = 0; g < 256; ++g) EXPECT_EQ(none.level[g], g);
}

TEST(MatchPhotometric, GainIsBoundedWhenTheContentDiffers) {
  const int w = 32, h = 32;
  const auto left = textured(w, h);
  std::vector<std::uint8_t> right(left.size());
  // Nearly flat: block rows alternate 128 and 129.
  for (std::size_t i = 0; i < right.size(); ++i)
    right[i] = static_cast<std::uint8_t>(128 + (i / w / 2) % 2);
  const ConstGray8View l(left.data(), w, h), r(right.data(), w, h);
  const GrayMap m = right_to_left_gray_map(l, {0, 0, w, h}, r, {0, 0, w, h});
  EXPECT_EQ(m.gain_q8, 256 * kMaxGrayGain);
  for (int g = 1; g < 256; ++g) EXPECT_GE(m.level[g], m.level[g - 1]);  // still increasing
}

// The pairs' map: `right` is `left` shifted by `d` columns, so left column
// x and right column x - d see the same point; every `wrong`-th pair is
// given a wrong right column (a mismatched edge pair).
GrayMap map_of_pairs(ConstGray8View l, ConstGray8View r, int d, int wrong) {
  PairGainVotes votes;
  PairOffsetVotes sums;
  auto each_pair = [&](auto& sink) {
    int k = 0;
    for (int y = 4; y < l.height() - 4; y += 2)
      for (int x = d + 4; x < l.width() - 4; x += 3, ++k)
        sink.add(l, x, r, (wrong > 0 && k % wrong == 0) ? x - d + 7 : x - d, y);
  };
  each_pair(votes);
  sums.gain_q8 = votes.median_gain_q8();
  each_pair(sums);
  return gray_map_from_pairs(sums);
}

// A shifted copy of `left` through v -> gain v + offset (rounded, clamped).
std::vector<std::uint8_t> other_camera(const std::vector<std::uint8_t>& left, int w, int d,
                                       double gain, double offset) {
  std::vector<std::uint8_t> right(left.size());
  for (std::size_t i = 0; i < left.size(); ++i) {
    const int x = static_cast<int>(i % static_cast<std::size_t>(w));
    const std::size_t src =
        i - static_cast<std::size_t>(x) + static_cast<std::size_t>(std::min(x + d, w - 1));
    right[i] =
        static_cast<std::uint8_t>(std::clamp(std::lround(gain * left[src] + offset), 0L, 255L));
  }
  return right;
}

TEST(MatchPhotometric, PairsUndoAGainAndAnOffsetDespiteWrongPairs) {
  const int w = 96, h = 48, d = 9;
  const auto left = textured(w, h);
  const auto right = other_camera(left, w, d, 0.82, 12.0);
  const ConstGray8View l(left.data(), w, h), r(right.data(), w, h);
  for (int wrong : {0, 5}) {  // none, one pair in five
    const GrayMap m = map_of_pairs(l, r, d, wrong);
    EXPECT_NEAR(m.gain_q8, 256 / 0.82, 4.0) << wrong;
    EXPECT_NEAR(m(static_cast<std::uint8_t>(0.82 * 128 + 12)), 128, 1) << wrong;
  }
}

TEST(MatchPhotometric, PairsOfEqualCamerasGiveTheIdentity) {
  const int w = 96, h = 48, d = 9;
  const auto left = textured(w, h);
  const auto right = other_camera(left, w, d, 1.0, 1.0);  // within what the map resolves
  const ConstGray8View l(left.data(), w, h), r(right.data(), w, h);
  const GrayMap m = map_of_pairs(l, r, d, 5);
  EXPECT_EQ(m.gain_q8, 256);
  for (int g = 0; g < 256; ++g) EXPECT_EQ(m.level[g], g);
  const auto brighter = other_camera(left, w, d, 1.0, 4.0);  // beyond it: mapped
  EXPECT_EQ(map_of_pairs(l, ConstGray8View(brighter.data(), w, h), d, 5)(104), 100);
}

TEST(MatchPhotometric, TooFewPairsGiveTheIdentity) {
  PairOffsetVotes votes;
  votes.gain_q8 = 300;
  votes.votes[kMaxOffset2 + 40] = kMinMapPairs - 1;  // 20 levels
  votes.pairs = kMinMapPairs - 1;
  EXPECT_EQ(gray_map_from_pairs(votes).gain_q8, 256);
  votes.votes[kMaxOffset2 + 40] = votes.pairs = kMinMapPairs;
  EXPECT_EQ(gray_map_from_pairs(votes).gain_q8, 300);
  EXPECT_EQ(gray_map_from_pairs(votes).offset_q8, 20 * 256);
  EXPECT_EQ(PairGainVotes{}.median_gain_q8(), 256);
}

TEST(MatchPhotometric, NoHeap) {
  const int w = 64, h = 48;
  const auto px = textured(w, h);
  const ConstGray8View v(px.data(), w, h);
  std::uint8_t row[64];
  const test::HeapScope heap;
  const GrayMap m = right_to_left_gray_map(v, {8, 8, 32, 32}, v, {8, 8, 32, 32});
  apply_gray_map(m, px.data(), 64, row);
  EXPECT_EQ(heap.allocations(), 0u);
  EXPECT_EQ(row[5], px[5]);  // same areas: the identity
}

}  // namespace
}  // namespace petra::match
