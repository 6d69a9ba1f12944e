#include "algo/stereo/disparity_median.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "algo/core/disparity.hpp"
#include "tests/support/heap_counter.hpp"

namespace petra {
namespace {

// Straightforward reference: sort the valid neighbours.
std::vector<std::int16_t> reference_median(const std::vector<std::int16_t>& d, int w, int h) {
  std::vector<std::int16_t> out = d;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if (!is_valid_disparity(d[static_cast<std::size_t>(y) * w + x])) continue;
      std::vector<std::int16_t> v;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int xx = x + dx, yy = y + dy;
          if (xx < 0 || yy < 0 || xx >= w || yy >= h) continue;
          const std::int16_t q = d[static_cast<std::size_t>(yy) * w + xx];
          if (is_valid_disparity(q)) v.push_back(q);
        }
      if (v.size() < 5) continue;
      std::sort(v.begin(), v.end());
      out[static_cast<std::size_t>(y) * w + x] = v[v.size() / 2];
    }
  return out;
}

TEST(DisparityMedian, MatchesASortingReferenceWithInvalidNeighbours) {
  std::mt19937 rng(8);
  for (int trial = 0; trial < 30; ++trial) {
    const int w = 17 + trial, h = 9 + trial % 7;
    std::vector<std::int16_t> d(static_cast<std::size_t>(w) * h);
    for (auto& q : d)
      q = (rng() % 100) < static_cast<unsigned>(trial * 2)
              ? kInvalidDisparity
              : static_cast<std::int16_t>(static_cast<int>(rng() % 2000) - 300);
    const auto expect = reference_median(d, w, h);
    std::vector<std::int16_t> scratch(median3x3_scratch(w));
    ASSERT_TRUE(median3x3_valid(ImageView<std::int16_t>(d.data(), w, h), scratch).ok());
    EXPECT_EQ(d, expect) << "trial " << trial;
  }
}

TEST(DisparityMedian, RemovesASpikeAndAllocatesNothing) {
  std::vector<std::int16_t> d(10 * 10, 160), scratch(median3x3_scratch(10));
  d[55] = 900;
  petra::test::HeapScope scope;
  ASSERT_TRUE(median3x3_valid(ImageView<std::int16_t>(d.data(), 10, 10), scratch).ok());
  EXPECT_EQ(scope.allocations(), 0u);
  EXPECT_EQ(d[55], 160);
  std::vector<std::int16_t> small(3);
  EXPECT_EQ(median3x3_valid(ImageView<std::int16_t>(d.data(), 10, 10), small).code(),
            Errc::capacity_exceeded);
}

}  // namespace
}  // namespace petra
