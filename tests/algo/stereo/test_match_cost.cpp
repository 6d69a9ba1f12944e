#include "algo/stereo/match_cost.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <vector>

namespace petra {
namespace {

using match::kRawPad;
using match::kSlantLaneOffset;
using match::kWindowRows;

// Nine raw cost rows of wc columns x stride lanes, random 0..24 (kRawPad on
// the lanes past `lanes`, as raw_cost_row leaves them).
std::vector<std::vector<std::uint8_t>> raw_window(int wc, int stride, int lanes, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> cost(0, match::kRawMax);
  std::vector<std::vector<std::uint8_t>> rows(kWindowRows);
  for (auto& r : rows) {
    r.resize(static_cast<std::size_t>(wc) * stride);
    for (std::size_t m = 0; m < r.size(); ++m)
      r[m] = static_cast<int>(m % stride) < lanes ? static_cast<std::uint8_t>(cost(rng)) : kRawPad;
  }
  return rows;
}

// Row j at lane k + offset[j]; a lane outside the column reads kRawPad.
std::uint16_t slanted_sum(const std::vector<std::vector<std::uint8_t>>& rows, int i, int k,
                          int stride) {
  int sum = 0;
  for (int j = 0; j < kWindowRows; ++j) {
    const int kk = k + kSlantLaneOffset[j];
    sum += (kk >= 0 && kk < stride) ? rows[j][static_cast<std::size_t>(i) * stride + kk] : kRawPad;
  }
  return static_cast<std::uint16_t>(sum);
}

template <int kLanes>
void expect_slanted_sums(int stride, int lanes) {
  const int wc = 13;
  const auto rows = raw_window(wc, stride, lanes, 7u + static_cast<unsigned>(stride));
  const std::uint8_t* ptrs[kWindowRows];
  for (int j = 0; j < kWindowRows; ++j) ptrs[j] = rows[j].data();
  std::vector<std::uint16_t> got(static_cast<std::size_t>(wc) * stride, 0xFFFF);
  match::slanted_column_sums<kLanes>(ptrs, wc, stride, got.data());
  for (int i = 0; i < wc; ++i)
    for (int k = 0; k < stride; ++k)
      ASSERT_EQ(got[static_cast<std::size_t>(i) * stride + k], slanted_sum(rows, i, k, stride))
          << "column " << i << " lane " << k << " (stride " << stride << ")";
}

TEST(MatchCost, SlantedColumnSumsReadEachRowAtItsOffset) {
  expect_slanted_sums<16>(16, 11);
  expect_slanted_sums<32>(32, 32);
  expect_slanted_sums<0>(48, 40);  // the generic lane count
}

TEST(MatchCost, SlantedOffsetsAreHalfAPixelPerRow) {
  for (int j = 0; j < kWindowRows; ++j) {
    const double half = 0.5 * (j - match::kBoxRadiusY);
    EXPECT_EQ(kSlantLaneOffset[j], static_cast<int>(half < 0 ? half - 0.5 : half + 0.5)) << j;
  }
}

TEST(MatchCost, PoorlyMatchedPixelsAreThoseWithNoCheapDisparity) {
  const int n = 3, stride = 16;
  std::vector<std::uint16_t> agg(n * stride, 500);
  agg[0 * stride + 7] = 110;  // column 0: a disparity at the limit
  agg[1 * stride + 3] = 111;  // column 1: just above it
  agg[2 * stride + 15] = 20;  // column 2: a good match in its last lane
  std::uint8_t poor[n] = {9, 9, 9};
  EXPECT_EQ(match::poorly_matched<16>(agg.data(), n, stride, 110, poor), 1);
  EXPECT_EQ(poor[0], 0);
  EXPECT_EQ(poor[1], 1);
  EXPECT_EQ(poor[2], 0);
}

TEST(MatchCost, KeepCheaperChargesTheOtherItsPenaltyWhereAsked) {
  const int n = 3, stride = 16;
  std::vector<std::uint16_t> agg(n * stride), other(agg.size());
  for (int m = 0; m < n * stride; ++m) {
    agg[m] = static_cast<std::uint16_t>(100 + m);
    other[m] = static_cast<std::uint16_t>(m % 2 ? 80 + m : 95 + m);
  }
  const std::uint8_t where[n] = {0, 1, 1};
  match::keep_cheaper<16>(agg.data(), other.data(), n, stride, 10, where);
  for (int m = 0; m < n * stride; ++m) {
    const int want = m < stride ? 100 + m : (m % 2 ? 90 + m : 100 + m);  // 80 + 10 < 100
    EXPECT_EQ(agg[m], want) << m;
  }
}

}  // namespace
}  // namespace petra
