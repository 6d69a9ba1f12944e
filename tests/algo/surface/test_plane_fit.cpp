#include "algo/surface/plane_fit.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "algo/surface/fixed_point.hpp"

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

TEST(PlaneFit, WeightsSelectAndScale) {
  std::mt19937 rng(5);
  std::normal_distribution<double> g(0.0, 0.3);
  std::uniform_real_distribution<double> u(-50, 50);
  std::vector<V> pts;
  for (int i = 0; i < 4000; ++i) pts.push_back(V(u(rng), u(rng), 0.2 * (i % 7) + g(rng)));
  auto get = [&](std::size_t i) -> const V& { return pts[i]; };
  // Weight 0 drops a point; equal weights give the plain fit.
  auto plain = fit_plane_tls<double>(pts, [](std::size_t i) { return i % 3 != 0; });
  auto weighted = fit_plane_wtls_by<double>(pts.size(), get,
                                            [](std::size_t i) { return i % 3 != 0 ? 2.5 : 0.0; });
  ASSERT_TRUE(plain.ok() && weighted.ok());
  EXPECT_LT((plain->plane.normal - weighted->plane.normal).norm(), 1e-9);
  EXPECT_NEAR(plain->rms, weighted->rms, 1e-9);
  EXPECT_EQ(weighted->count, plain->count);
  auto none = fit_plane_wtls_by<double>(pts.size(), get, [](std::size_t) { return 0.0; });
  EXPECT_FALSE(none.ok());
}

// A face seen 60 deg from its normal, its points displaced along their
// viewing rays (as a disparity error does): total least squares tilts the
// normal away from the ray, the fit along the ray does not.
TEST(PlaneFit, AlongTheRayFitsDepthNoiseWithoutTilt) {
  const V eye(0, 0, 0);
  const V centre(0, 0, 700);
  const double tilt = 60 * M_PI / 180;
  const V n(std::sin(tilt), 0, -std::cos(tilt));  // faces the camera (at the origin)
  const V e1 = V(0, 1, 0), e2 = n.cross(e1);
  double tls_err = 0, ray_err = 0;
  for (int seed = 1; seed <= 5; ++seed) {
    std::mt19937 rng(static_cast<unsigned>(seed));
    std::normal_distribution<double> depth(0.0, 2.0);
    std::uniform_real_distribution<double> u(-20, 20);
    std::vector<V> pts;
    for (int i = 0; i < 8000; ++i) {
      const V p = centre + u(rng) * e1 + u(rng) * e2;
      pts.push_back(p + depth(rng) * (p - eye).normalized());
    }
    auto get = [&](std::size_t i) -> const V& { return pts[i]; };
    auto one = [](std::size_t) { return 1.0; };
    auto t = fit_plane_wtls_by<double>(pts.size(), get, one);
    auto r = fit_plane_along_by<double>(pts.size(), get, one, V((centre - eye).normalized()));
    ASSERT_TRUE(t.ok() && r.ok());
    auto err = [&](const V& m) {
      return std::acos(std::min(1.0, std::abs(m.dot(n)))) * 180 / M_PI;
    };
    tls_err += err(t->plane.normal) / 5;
    ray_err += err(r->plane.normal) / 5;
  }
  std::printf("oblique face, 2 mm depth noise: normal error TLS %.2f deg, along the ray %.2f deg\n",
              tls_err, ray_err);
  EXPECT_LT(ray_err, 0.3);
  EXPECT_GT(tls_err, 2 * ray_err);
}

TEST(PlaneFit, AlongTheRayNeedsAFootprint) {
  std::vector<V> line;
  for (int i = 0; i < 10; ++i) line.push_back(V(i, 0, 100 + i));
  auto f = fit_plane_along_by<double>(
      line.size(), [&](std::size_t i) -> const V& { return line[i]; },
      [](std::size_t) { return 1.0; }, V(0, 0, 1));
  ASSERT_FALSE(f.ok());
  EXPECT_NE(std::string(f.error().message).find("collinear"), std::string::npos);
}

// Written over the scalar type like the TLS fit: Q31.32 gives the double
// plane for the weighted and the along-the-ray fits.
TEST(PlaneFit, WeightedAndAlongTheRayFitsRunInFixedPoint) {
  using Q = Q31_32;
  using VQ = Vec3T<Q>;
  std::mt19937 rng(9);
  std::normal_distribution<double> depth(0.0, 1.0);
  std::uniform_real_distribution<double> u(-20, 20);
  const V n = V(0.5, -0.2, -0.8).normalized(), e1 = n.unitOrthogonal(), e2 = n.cross(e1);
  std::vector<V> pts;
  std::vector<VQ> qpts;
  for (int i = 0; i < 2000; ++i) {
    const V p = V(10, -5, 700) + u(rng) * e1 + u(rng) * e2;
    pts.push_back(p + depth(rng) * p.normalized());
    qpts.push_back(VQ(Q(pts.back().x()), Q(pts.back().y()), Q(pts.back().z())));
  }
  const V ray = V(10, -5, 700).normalized();
  const VQ qray(Q(ray.x()), Q(ray.y()), Q(ray.z()));
  auto w = [](std::size_t i) { return i % 5 != 0 ? 1.0 : 0.0; };
  auto wq = [](std::size_t i) { return i % 5 != 0 ? Q(1.0) : Q(0.0); };
  auto get = [&](std::size_t i) -> const V& { return pts[i]; };
  auto getq = [&](std::size_t i) -> const VQ& { return qpts[i]; };
  auto td = fit_plane_wtls_by<double>(pts.size(), get, w);
  auto tq = fit_plane_wtls_by<Q>(qpts.size(), getq, wq);
  auto rd = fit_plane_along_by<double>(pts.size(), get, w, ray);
  auto rq = fit_plane_along_by<Q>(qpts.size(), getq, wq, qray);
  ASSERT_TRUE(td.ok() && tq.ok() && rd.ok() && rq.ok());
  auto to_v = [](const VQ& q) {
    return V(q.x().to_double(), q.y().to_double(), q.z().to_double());
  };
  auto deg = [](const V& a, const V& b) {
    return std::atan2(a.cross(b).norm(), std::abs(a.dot(b))) * 180 / M_PI;
  };
  EXPECT_LT(deg(td->plane.normal, to_v(tq->plane.normal)), 1e-4);
  EXPECT_LT(deg(rd->plane.normal, to_v(rq->plane.normal)), 1e-4);
  EXPECT_NEAR(rd->rms, rq->rms.to_double(), 1e-4);
}

}  // namespace
}  // namespace petra
