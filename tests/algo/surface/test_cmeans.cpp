#include "algo/surface/cmeans.hpp"

#include <gtest/gtest.h>

#include <cstdio>

#include <Eigen/LU>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "tests/support/heap_counter.hpp"

namespace petra {
namespace {

using V = Eigen::Vector3d;

TEST(CMeans, Eq9InitialPartitionByComponentSums) {
  // Sums 0, 1, 2, 3, 4 with c = 3: a = 2 s / 4 + 1 = 1, 1.5, 2, 2.5, 3
  // -> round half up -> classes 1, 2, 2, 3, 3 (0-based 0, 1, 1, 2, 2).
  const std::vector<V> x = {{0, 0, 0}, {1, 0, 0}, {0, 1, 1}, {1, 1, 1}, {2, 1, 1}};
  std::vector<std::uint8_t> labels(x.size());
  ASSERT_TRUE(cmeans_initial_partition<double>(x, 3, labels).ok());
  EXPECT_EQ(labels, (std::vector<std::uint8_t>{0, 1, 1, 2, 2}));
  // Equal sums (normals (1,0,0), (0,1,0), (0,0,1)): the widest component orders them.
  const std::vector<V> same = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0.5, 0.5, 0}};
  std::vector<std::uint8_t> l2(same.size());
  ASSERT_TRUE(cmeans_initial_partition<double>(same, 2, l2).ok());
  EXPECT_EQ(l2, (std::vector<std::uint8_t>{1, 0, 0, 1}));  // x: 1, 0, 0, 0.5 -> a: 2, 1, 1, 1.5
}

TEST(CMeans, Eq11DistanceByHand) {
  // Two classes whose statistics are easy by hand. Class A: (+-1, 0, 0),
  // (0, +-2, 0), (0, 0, +-3) around (0, 0, 0): u = 0, Sigma = diag(2, 8, 18)/6
  // = diag(1/3, 4/3, 3). Class B: the same shape around (20, 20, 20).
  std::vector<V> x;
  for (const V& c : {V(0, 0, 0), V(20, 20, 20)})
    for (const V& d : {V(1, 0, 0), V(-1, 0, 0), V(0, 2, 0), V(0, -2, 0), V(0, 0, 3), V(0, 0, -3)})
      x.push_back(c + d);
  std::vector<std::uint8_t> labels(x.size());
  CMeansParams p;
  p.regularisation = 1e-12;  // negligible here
  auto r = cmeans<double>(x, 2, p, labels);
  ASSERT_TRUE(r.ok()) << r.error().message;
  EXPECT_TRUE(r->converged);
  EXPECT_EQ(r->iterations, 1);  // eq. 9 already separates them; nothing moves
  for (std::size_t i = 0; i < x.size(); ++i) EXPECT_EQ(labels[i], i < 6 ? 0 : 1);
  const auto& a = r->classes[0];
  EXPECT_EQ(a.count, 6u);
  EXPECT_LT(a.mean.norm(), 1e-12);
  EXPECT_NEAR(a.covariance(0, 0), 1.0 / 3, 1e-9);
  EXPECT_NEAR(a.covariance(1, 1), 4.0 / 3, 1e-9);
  EXPECT_NEAR(a.covariance(2, 2), 3.0, 1e-9);
  EXPECT_NEAR(a.covariance(0, 1), 0.0, 1e-12);
  EXPECT_LT((r->classes[1].mean - V(20, 20, 20)).norm(), 1e-12);
  // d(x, A) for x = (1, 1, 1): ln(1/3 * 4/3 * 3) + (3 + 3/4 + 1/3) - 2 ln(6/12)
  //                          = ln(4/3) + 49/12 + 2 ln 2 = 5.75731...
  const double expected = std::log(4.0 / 3) + 49.0 / 12 + 2 * std::log(2.0);
  const Ldlt3<double> f = ldlt3<double>(a.covariance);
  const double d = f.log_det() + f.mahalanobis(V(1, 1, 1) - a.mean) - 2 * std::log(6.0 / 12);
  EXPECT_NEAR(d, expected, 1e-9);
  EXPECT_NEAR(expected, 5.75731, 1e-5);
}

TEST(CMeans, MovesSamplesUntilNoneChangesClass) {
  // Group A is long along (1,1,1), so eq. 9 (which orders by the component
  // sum) starts its far end in B's class; eq. 11's Mahalanobis term, which
  // sees A's shape, must bring those samples back.
  std::mt19937 rng(4);
  std::normal_distribution<double> g(0.0, 1.0);
  std::vector<V> x;
  std::vector<int> truth;
  for (int i = 0; i < 300; ++i) {
    const bool a = i % 3 != 0;
    if (a) {
      x.push_back(V::Ones() / std::sqrt(3.0) * 3.0 * g(rng) + 0.2 * V(g(rng), g(rng), g(rng)));
    } else {
      x.push_back(V(5, 5, 5) + 0.3 * V(g(rng), g(rng), g(rng)));
    }
    truth.push_back(a ? 0 : 1);
  }
  std::vector<std::uint8_t> labels(x.size());
  ASSERT_TRUE(cmeans_initial_partition<double>(x, 2, labels).ok());
  std::size_t wrong_at_start = 0;
  for (std::size_t i = 0; i < x.size(); ++i) wrong_at_start += labels[i] != truth[i];
  EXPECT_GT(wrong_at_start, 3u);
  auto r = cmeans<double>(x, 2, CMeansParams{}, labels);
  ASSERT_TRUE(r.ok());
  EXPECT_TRUE(r->converged);
  EXPECT_GT(r->iterations, 1);
  // A few of A's samples lie in its 3-sigma tail next to B; whether eq. 11
  // puts such a borderline sample in A or B turns on the last bits of the
  // arithmetic (aarch64's fused multiply-add flips one), so allow two.
  std::size_t wrong_at_end = 0;
  for (std::size_t i = 0; i < x.size(); ++i) wrong_at_end += labels[i] != truth[i];
  std::printf("C-means: %zu of %zu samples in the wrong class at the start, %zu at the end\n",
              wrong_at_start, x.size(), wrong_at_end);
  EXPECT_LE(wrong_at_end, 2u);
  EXPECT_LT(wrong_at_end * 5, wrong_at_start);
}

TEST(CMeans, SingularCovarianceAndEmptyClassesAreGuarded) {
  // All samples on the plane z = 0 (every covariance singular), three groups.
  std::vector<V> x;
  for (int k = 0; k < 3; ++k)
    for (int i = 0; i < 20; ++i) x.push_back(V(10.0 * k + 0.1 * (i % 5), 0.1 * (i / 5), 0));
  std::vector<std::uint8_t> labels(x.size());
  auto r = cmeans<double>(x, 3, CMeansParams{}, labels);
  ASSERT_TRUE(r.ok()) << r.error().message;
  for (int j = 0; j < 3; ++j) {
    EXPECT_EQ(r->classes[j].count, 20u);
    EXPECT_TRUE(r->classes[j].mean.allFinite());
    EXPECT_GT(r->classes[j].covariance(2, 2), 0.0);  // regularised
  }
  // Two tight groups but c = 3: one class would be empty; it is re-seeded.
  std::vector<V> two;
  for (int i = 0; i < 30; ++i) two.push_back(V(i < 15 ? 0.0 : 10.0, 0.01 * i, 0.02 * (i % 3)));
  two.push_back(V(5, 0, 0));  // the middle of eq. 9's range is empty otherwise
  two.pop_back();
  std::vector<std::uint8_t> l2(two.size());
  auto r2 = cmeans<double>(two, 3, CMeansParams{}, l2);
  ASSERT_TRUE(r2.ok()) << r2.error().message;
  EXPECT_GE(r2->reseeded, 1u);
  for (int j = 0; j < 3; ++j) EXPECT_GT(r2->classes[j].count, 0u);
}

TEST(CMeans, BadInputIsNamed) {
  std::vector<V> x = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  std::vector<std::uint8_t> labels(x.size());
  auto r = cmeans<double>(x, 1, CMeansParams{}, labels);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.code(), Errc::out_of_range);
  EXPECT_NE(std::string(r.error().message).find("c = 1"), std::string::npos);
  EXPECT_EQ(cmeans<double>(x, 9, CMeansParams{}, labels).code(), Errc::out_of_range);
  r = cmeans<double>(x, 4, CMeansParams{}, labels);
  EXPECT_NE(std::string(r.error().message).find("3 samples for c = 4"), std::string::npos);
  std::vector<V> same(5, V(1, 2, 3));
  std::vector<std::uint8_t> l5(5);
  r = cmeans<double>(same, 2, CMeansParams{}, l5);
  EXPECT_NE(std::string(r.error().message).find("all 5 samples are equal"), std::string::npos);
  CMeansParams p;
  p.regularisation = 0;
  EXPECT_EQ(cmeans<double>(x, 2, p, labels).code(), Errc::invalid_argument);
  std::vector<std::uint8_t> short_labels(2);
  EXPECT_EQ(cmeans<double>(x, 2, CMeansParams{}, short_labels).code(), Errc::invalid_argument);
}

TEST(CMeans, NoHeap) {
  std::mt19937 rng(1);
  std::normal_distribution<double> g(0.0, 1.0);
  std::vector<V> x(3000);
  for (std::size_t i = 0; i < x.size(); ++i)
    x[i] = V(g(rng), g(rng), g(rng)) + V(5.0 * static_cast<int>(i % 3), 0, 0);
  std::vector<std::uint8_t> labels(x.size());
  test::HeapScope scope;
  auto r = cmeans<double>(x, 3, CMeansParams{}, labels);
  EXPECT_EQ(scope.allocations(), 0u);
  EXPECT_TRUE(r.ok());
}

}  // namespace
}  // namespace petra
