#include "algo/plane_fit.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>
#include <string>
#include <vector>

namespace petra {
namespace {

using V = Eigen::Vector3d;

TEST(PlaneFit, ExactPlaneIsRecovered) {
  const V n = V(0.3, -0.5, 0.8).normalized();
  const double d = -42.0;
  const V u = n.unitOrthogonal(), w = n.cross(u);
  std::vector<V> pts;
  for (int i = 0; i < 10; ++i)
    for (int j = 0; j < 7; ++j)
      pts.push_back(-d * n + 13.0 * i * u + 5.0 * j * w + V(300, -200, 700) -
                    n.dot(V(300, -200, 700)) * n);
  auto f = fit_plane_tls<double>(pts);
  ASSERT_TRUE(f.ok()) << f.error().message;
  const V got = f->plane.normal.dot(n) > 0 ? f->plane.normal : V(-f->plane.normal);
  EXPECT_LT((got - n).norm(), 1e-12);
  EXPECT_NEAR(std::abs(f->plane.d), std::abs(d), 1e-9);
  EXPECT_LT(f->rms, 1e-9);
  EXPECT_EQ(f->count, pts.size());
  for (const V& p : pts) EXPECT_NEAR(f->plane.distance(p), 0.0, 1e-9);
}

TEST(PlaneFit, RmsIsTheOrthogonalScatter) {
  std::mt19937 rng(3);
  std::normal_distribution<double> g(0.0, 0.5);
  std::uniform_real_distribution<double> u(-100, 100);
  std::vector<V> pts;
  for (int i = 0; i < 20000; ++i) pts.push_back(V(u(rng), u(rng), 10.0 + g(rng)));
  auto f = fit_plane_tls<double>(pts);
  ASSERT_TRUE(f.ok());
  EXPECT_NEAR(f->rms, 0.5, 0.01);
  EXPECT_GT(std::abs(f->plane.normal.z()), 1.0 - 1e-5);
  // Only the selected points count.
  auto half = fit_plane_tls<double>(pts, [](std::size_t i) { return i % 2 == 0; });
  ASSERT_TRUE(half.ok());
  EXPECT_EQ(half->count, 10000u);
}

TEST(PlaneFit, DegenerateInputIsNamed) {
  std::vector<V> two = {V(0, 0, 0), V(1, 0, 0)};
  auto f = fit_plane_tls<double>(two);
  ASSERT_FALSE(f.ok());
  EXPECT_NE(std::string(f.error().message).find("need at least 3"), std::string::npos);
  std::vector<V> line;
  for (int i = 0; i < 10; ++i) line.push_back(V(i, 2.0 * i, -i));
  f = fit_plane_tls<double>(line);
  ASSERT_FALSE(f.ok());
  EXPECT_NE(std::string(f.error().message).find("collinear"), std::string::npos);
  std::vector<V> same(5, V(1, 2, 3));
  f = fit_plane_tls<double>(same);
  EXPECT_NE(std::string(f.error().message).find("coincide"), std::string::npos);
}

}  // namespace
}  // namespace petra
