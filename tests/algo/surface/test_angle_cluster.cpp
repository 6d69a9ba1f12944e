#include "algo/surface/angle_cluster.hpp"
#include "tests/support/angles.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>
#include <string>
#include <vector>

namespace petra {
namespace {

using V = Eigen::Vector3d;

// Normals scattered by ~3 degrees around three directions 40+ degrees apart.
struct Data {
  std::vector<V> normals;
  std::vector<double> weights;
  std::vector<int> truth;
  V dirs[3] = {V(0, 0, 1), V(0.7, 0, 0.7).normalized(), V(-0.2, -0.8, 0.55).normalized()};
};

Data make_data() {
  Data d;
  std::mt19937 rng(2);
  std::normal_distribution<double> g(0.0, 0.05);
  for (int i = 0; i < 900; ++i) {
    const int k = i % 3;
    d.normals.push_back((d.dirs[k] + V(g(rng), g(rng), g(rng))).normalized());
    d.weights.push_back(1.0 + (i % 5));
    d.truth.push_back(k);
  }
  return d;
}

TEST(AngleCluster, ConvergesToTheWeightedMeanDirections) {
  const Data d = make_data();
  const V init[3] = {V(0.1, 0, 1).normalized(), V(1, 0, 1).normalized(),
                     V(0, -1, 0.5).normalized()};
  std::vector<std::uint8_t> labels(d.normals.size());
  auto r = angle_cluster<double>(d.normals, d.weights, init, {}, labels);
  ASSERT_TRUE(r.ok()) << r.error().message;
  EXPECT_TRUE(r->converged);
  ASSERT_EQ(r->c, 3);
  for (std::size_t i = 0; i < labels.size(); ++i) EXPECT_EQ(labels[i], d.truth[i]) << i;
  for (int k = 0; k < 3; ++k) {
    V mean = V::Zero();
    for (std::size_t i = 0; i < labels.size(); ++i)
      if (labels[i] == k) mean += d.weights[i] * d.normals[i];
    EXPECT_LT(test::angle_deg(r->centres[k], mean.normalized()),
              1e-9);  // the centre is the weighted mean
    EXPECT_LT(test::angle_deg(r->centres[k], d.dirs[k]), 1.0);
  }
}

TEST(AngleCluster, InitialCentresCloserThanFiveDegreesAreReplacedOrDropped) {
  const Data d = make_data();
  // Second centre 3 degrees from the first: replaced by the normal farthest
  // from the kept centres, so the three groups are still found.
  const V a(0, 0, 1);
  const V b = Eigen::AngleAxisd(3 * M_PI / 180, V::UnitX()) * a;
  const V init[3] = {a, b, V(0.7, 0, 0.7).normalized()};
  std::vector<std::uint8_t> labels(d.normals.size());
  auto r = angle_cluster<double>(d.normals, d.weights, init, {}, labels);
  ASSERT_TRUE(r.ok());
  ASSERT_EQ(r->c, 3);
  for (int i = 0; i < r->c; ++i)
    for (int j = i + 1; j < r->c; ++j)
      EXPECT_GT(test::angle_deg(r->centres[i], r->centres[j]), 5.0);
  // All normals within 2 degrees of one direction: only one centre survives.
  std::vector<V> one(50);
  std::vector<double> w(50, 1.0);
  for (int i = 0; i < 50; ++i)
    one[static_cast<std::size_t>(i)] =
        (V(0, 0, 1) + V(0.01 * (i % 3), 0.01 * (i % 2), 0)).normalized();
  std::vector<std::uint8_t> l1(50);
  const V close[3] = {a, b, Eigen::AngleAxisd(3 * M_PI / 180, V::UnitY()) * a};
  auto r1 = angle_cluster<double>(one, w, close, {}, l1);
  ASSERT_TRUE(r1.ok());
  EXPECT_EQ(r1->c, 1);
}

TEST(AngleCluster, BadInputIsNamed) {
  std::vector<V> n = {V(0, 0, 1)};
  std::vector<double> w = {1.0};
  std::vector<std::uint8_t> l(1);
  const V init[9] = {};
  EXPECT_EQ(angle_cluster<double>(n, w, std::span<const V>(init, 0), {}, l).code(),
            Errc::out_of_range);
  EXPECT_EQ(angle_cluster<double>(n, w, std::span<const V>(init, 9), {}, l).code(),
            Errc::out_of_range);
  std::vector<double> w2 = {1.0, 2.0};
  EXPECT_EQ(angle_cluster<double>(n, w2, std::span<const V>(init, 1), {}, l).code(),
            Errc::invalid_argument);
  AngleClusterParams p;
  p.min_separation_deg = 95;
  EXPECT_EQ(angle_cluster<double>(n, w, std::span<const V>(init, 1), p, l).code(),
            Errc::invalid_argument);
}

}  // namespace
}  // namespace petra
