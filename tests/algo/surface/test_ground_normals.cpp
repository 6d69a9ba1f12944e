#include "algo/surface/ground_normals.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "tests/support/heap_counter.hpp"

namespace petra {
namespace {

const Eigen::Vector3d kUp = Eigen::Vector3d::UnitZ();

Eigen::Vector3d tilted(double deg, double azimuth_deg) {
  const double t = deg * M_PI / 180.0, a = azimuth_deg * M_PI / 180.0;
  return {std::sin(t) * std::cos(a), std::sin(t) * std::sin(a), std::cos(t)};
}

// Rough ground: normals scattered about the plane's by a few degrees, a tenth
// of them on pebbles' flanks at 40 deg.
TEST(GroundNormals, RoughGroundFacesAlongItsPlane) {
  std::mt19937 rng(7);
  std::normal_distribution<double> lean(0.0, 8.0);
  std::uniform_real_distribution<double> az(0.0, 360.0);
  std::vector<Eigen::Vector3d> n;
  for (int i = 0; i < 1000; ++i) n.push_back(tilted(i % 10 == 0 ? 40.0 : lean(rng), az(rng)));
  std::vector<PointClass> labels(n.size(), PointClass::ground);
  const GroundNormalShare s = ground_normal_share(n, labels, kUp, {});
  EXPECT_EQ(s.counted, 1000u);
  EXPECT_GT(s.share, 0.85);
  EXPECT_GE(s.share, GroundNormalParams{}.min_share);
}

// Two faces of a 110 deg ridge under a plane laid across them: every point leans 35 deg.
TEST(GroundNormals, TwoFacesOfARidgeDoNot) {
  std::vector<Eigen::Vector3d> n;
  for (int i = 0; i < 500; ++i) n.push_back(tilted(35.0, 0.0));
  for (int i = 0; i < 500; ++i) n.push_back(tilted(35.0, 180.0));
  std::vector<PointClass> labels(n.size(), PointClass::ground);
  const GroundNormalShare s = ground_normal_share(n, labels, kUp, {});
  EXPECT_EQ(s.counted, 1000u);
  EXPECT_LT(s.share, GroundNormalParams{}.min_share);
  EXPECT_DOUBLE_EQ(s.share, 0.0);
}

// Rock points and points without a normal are not counted.
TEST(GroundNormals, CountsGroundPointsWithANormalOnly) {
  std::vector<Eigen::Vector3d> n = {kUp, tilted(60, 0), Eigen::Vector3d::Zero(), tilted(10, 90)};
  std::vector<PointClass> labels = {PointClass::ground, PointClass::rock, PointClass::ground,
                                    PointClass::ground};
  test::HeapScope heap;
  const GroundNormalShare s = ground_normal_share(n, labels, kUp, {});
  EXPECT_EQ(heap.allocations(), 0u);
  EXPECT_EQ(s.counted, 2u);
  EXPECT_DOUBLE_EQ(s.share, 1.0);
  const GroundNormalShare none = ground_normal_share({}, {}, kUp, {});
  EXPECT_EQ(none.counted, 0u);
  EXPECT_DOUBLE_EQ(none.share, 1.0);
}

TEST(GroundNormals, BadParametersAreRefusedByName) {
  EXPECT_TRUE(validate(GroundNormalParams{}).ok());
  GroundNormalParams p;
  p.max_lean_deg = 90;
  EXPECT_NE(std::string(validate(p).error().message).find("max_lean_deg"), std::string::npos);
  p = {};
  p.min_share = 1.5;
  EXPECT_NE(std::string(validate(p).error().message).find("min_share"), std::string::npos);
}

}  // namespace
}  // namespace petra
