#include "algo/stereo/scanline_dp.hpp"

#include <gtest/gtest.h>

#include <random>
#include <vector>

namespace petra::match {
namespace {

constexpr int kLanes = 16;
constexpr int kSp = path_row_stride(kLanes);

struct Row {
  int n;
  std::vector<std::uint16_t> cost, p2;
  std::vector<std::int16_t> lo, hi, S, scratch;
  explicit Row(int n_)
      : n(n_),
        cost(static_cast<std::size_t>(n_) * kLanes),
        p2(n_),
        lo(n_, 0),
        hi(n_, kLanes - 1),
        S(static_cast<std::size_t>(n_) * kSp),
        scratch(static_cast<std::size_t>(n_) * kSp) {}
  int best(int x) const {
    const std::int16_t* s = S.data() + static_cast<std::size_t>(x) * kSp + kGuardLanes;
    int k = 0;
    for (int j = 1; j < kLanes; ++j)
      if (s[j] < s[k]) k = j;
    return k;
  }
  void run(int p1, int p2v) {
    for (auto& v : p2) v = static_cast<std::uint16_t>(p2v);
    apply_bounds<kLanes>(cost.data(), n, kLanes, lo.data(), hi.data(), kLanes - 1);
    scanline_dp<kLanes>({cost.data(), n, kLanes, p2.data(), p1}, S.data(), scratch.data());
  }
};

TEST(ScanlineDp, WithoutPenaltiesEachColumnTakesItsCheapestLane) {
  Row r(40);
  std::mt19937 rng(1);
  for (auto& c : r.cost) c = static_cast<std::uint16_t>(rng() % 1000);
  r.run(0, 0);
  for (int x = 0; x < r.n; ++x) {
    const std::uint16_t* c = r.cost.data() + static_cast<std::size_t>(x) * kLanes;
    EXPECT_EQ(c[r.best(x)], *std::min_element(c, c + kLanes)) << x;
  }
}

TEST(ScanlineDp, PenaltiesSmoothAwayAOneColumnOutlier) {
  Row r(30);
  for (int x = 0; x < r.n; ++x)
    for (int k = 0; k < kLanes; ++k)
      r.cost[static_cast<std::size_t>(x) * kLanes + k] = k == 5 ? 100 : 300;
  // Column 12 prefers lane 11 slightly.
  for (int k = 0; k < kLanes; ++k) r.cost[12 * kLanes + k] = k == 11 ? 250 : 300;
  r.run(20, 200);
  for (int x = 0; x < r.n; ++x) EXPECT_EQ(r.best(x), 5) << x;
}

TEST(ScanlineDp, ForbiddenLanesNeverWin) {
  Row r(30);
  std::mt19937 rng(4);
  for (auto& c : r.cost) c = static_cast<std::uint16_t>(rng() % 1080);
  for (int x = 0; x < r.n; ++x) {
    r.lo[static_cast<std::size_t>(x)] = static_cast<std::int16_t>(x % 8);
    r.hi[static_cast<std::size_t>(x)] = static_cast<std::int16_t>(x % 8 + 3);
  }
  r.run(67, 800);
  for (int x = 0; x < r.n; ++x) {
    EXPECT_GE(r.best(x), x % 8);
    EXPECT_LE(r.best(x), x % 8 + 3);
  }
}

// A cost row padded to 32 lanes whose DP runs over the first 16 (lanes =
// 16) gives exactly the path costs of a 16-lane row (path rows of 16 lanes);
// the pair kernel gives each row the single one's result.
TEST(ScanlineDp, SkippedPaddingLanesLeaveTheRealLanesUnchanged) {
  const int n = 50, wide = 32;
  std::mt19937 rng(9);
  std::vector<std::uint16_t> narrow_cost(static_cast<std::size_t>(n) * kLanes), p2(n);
  for (auto& c : narrow_cost) c = static_cast<std::uint16_t>(rng() % 1080);
  for (auto& v : p2) v = static_cast<std::uint16_t>(200 + rng() % 700);
  std::vector<std::uint16_t> wide_cost(static_cast<std::size_t>(n) * wide, 9999);
  for (int x = 0; x < n; ++x)
    for (int k = 0; k < kLanes; ++k)
      wide_cost[static_cast<std::size_t>(x) * wide + k] =
          narrow_cost[static_cast<std::size_t>(x) * kLanes + k];
  const std::size_t len = static_cast<std::size_t>(n) * kSp;
  std::vector<std::int16_t> s1(len), b1(len), s2(len), b2(len), s3(len), b3(len), s4(len), b4(len);
  scanline_dp<kLanes>({narrow_cost.data(), n, kLanes, p2.data(), 90}, s1.data(), b1.data());
  const ScanlineInputs in{wide_cost.data(), n, wide, p2.data(), 90, kLanes};
  scanline_dp<kLanes>(in, s2.data(), b2.data());
  scanline_dp_pair<0>(in, s3.data(), b3.data(), in, s4.data(), b4.data());
  for (int x = 0; x < n; ++x)
    for (int k = 0; k < kLanes; ++k) {
      const std::size_t at = static_cast<std::size_t>(x) * kSp + kGuardLanes + k;
      ASSERT_EQ(s1[at], s2[at]) << x << " " << k;
      ASSERT_EQ(s1[at], s3[at]) << x << " " << k;
      ASSERT_EQ(s1[at], s4[at]) << x << " " << k;
    }
}

// sum_paths = false leaves the forward path costs in S and the backward ones
// in the scratch: their sum is the summed S, lane by lane, guards untouched.
TEST(ScanlineDp, UnsummedPathsAddUpToTheSummedOnes) {
  const int n = 37;
  std::mt19937 rng(12);
  std::vector<std::uint16_t> cost(static_cast<std::size_t>(n) * kLanes), p2(n);
  for (auto& c : cost) c = static_cast<std::uint16_t>(rng() % 1080);
  for (auto& v : p2) v = static_cast<std::uint16_t>(150 + rng() % 800);
  const std::size_t len = static_cast<std::size_t>(n) * kSp;
  std::vector<std::int16_t> summed(len), b1(len), forward(len), backward(len), fp(len), bp(len),
      fq(len), bq(len);
  ScanlineInputs in{cost.data(), n, kLanes, p2.data(), 70};
  scanline_dp<kLanes>(in, summed.data(), b1.data());
  in.sum_paths = false;
  scanline_dp<kLanes>(in, forward.data(), backward.data());
  scanline_dp_pair<kLanes>(in, fp.data(), bp.data(), in, fq.data(), bq.data());
  int differ = 0;
  for (int x = 0; x < n; ++x) {
    const std::size_t row = static_cast<std::size_t>(x) * kSp + kGuardLanes;
    for (int k = 0; k < kLanes; ++k) {
      const std::size_t at = row + k;
      ASSERT_EQ(summed[at], forward[at] + backward[at]) << x << " " << k;
      ASSERT_EQ(fp[at], forward[at]) << x << " " << k;
      ASSERT_EQ(fq[at] + bq[at], summed[at]) << x << " " << k;
      differ += forward[at] != summed[at];
    }
    EXPECT_EQ(forward[row - 1], summed[row - 1]);  // guards
    EXPECT_EQ(forward[row + kLanes], summed[row + kLanes]);
  }
  EXPECT_GT(differ, n * kLanes / 2);  // the forward costs alone are not the sum
}

}  // namespace
}  // namespace petra::match
