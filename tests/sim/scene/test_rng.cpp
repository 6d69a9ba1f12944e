// The simulator's random numbers: reproducible per (seed, stream), streams
// independent, and with the distributions the scene model assumes.
#include "sim/scene/rng.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace petra::sim {
namespace {

TEST(Rng, SameSeedAndStreamRepeatOthersDiffer) {
  Rng a(7, 1), b(7, 1), c(7, 2), d(8, 1);
  int same_c = 0, same_d = 0;
  for (int i = 0; i < 1000; ++i) {
    const std::uint64_t x = a.next();
    EXPECT_EQ(x, b.next());
    same_c += x == c.next() ? 1 : 0;
    same_d += x == d.next() ? 1 : 0;
  }
  EXPECT_EQ(same_c, 0);
  EXPECT_EQ(same_d, 0);
}

TEST(Rng, DistributionsHaveTheirMoments) {
  Rng r(123, 4);
  constexpr int n = 200000;
  double sum = 0, sum2 = 0, lo = 1, hi = 0, nsum = 0, nsum2 = 0, hsum = 0, hsum2 = 0;
  std::vector<int> counts(6, 0);
  for (int i = 0; i < n; ++i) {
    const double u = r.uniform();
    lo = std::min(lo, u);
    hi = std::max(hi, u);
    sum += u;
    sum2 += u * u;
    const int k = r.integer(3, 8);
    ASSERT_GE(k, 3);
    ASSERT_LE(k, 8);
    ++counts[static_cast<std::size_t>(k - 3)];
    const double z = r.normal();
    nsum += z;
    nsum2 += z * z;
    const double h = hashed_normal(99, static_cast<std::uint64_t>(i));
    hsum += h;
    hsum2 += h * h;
  }
  EXPECT_GE(lo, 0.0);
  EXPECT_LT(hi, 1.0);
  EXPECT_NEAR(sum / n, 0.5, 0.005);
  EXPECT_NEAR(sum2 / n - 0.25, 1.0 / 12, 0.002);
  for (int c : counts) EXPECT_NEAR(c, n / 6.0, 0.03 * n / 6.0);
  EXPECT_NEAR(nsum / n, 0.0, 0.01);
  EXPECT_NEAR(nsum2 / n, 1.0, 0.02);
  EXPECT_NEAR(hsum / n, 0.0, 0.01);
  EXPECT_NEAR(hsum2 / n, 1.0, 0.02);
  EXPECT_EQ(hashed_normal(5, 17), hashed_normal(5, 17));
  EXPECT_NE(hashed_normal(5, 17), hashed_normal(5, 18));
}

}  // namespace
}  // namespace petra::sim
