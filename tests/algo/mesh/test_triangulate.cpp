#include "algo/mesh/triangulate.hpp"

#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "tests/support/heap_counter.hpp"
#include "tests/support/test_rig.hpp"

namespace petra {
namespace {

TEST(Triangulate, Eq8RecoversExactProjectionsWithDistortion) {
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    const StereoRig rig = test::bumblebee_rig(seed, -0.004 + 0.001 * static_cast<double>(seed));
    const auto l = eq8_camera<double>(rig.left), r = eq8_camera<double>(rig.right);
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    double worst = 0;
    for (int i = 0; i < 500; ++i) {
      const Eigen::Vector3d pc(300 * u(rng), 200 * u(rng), 800 + 300 * u(rng));
      const Eigen::Vector3d pw = camera_to_world(rig.left, pc);
      auto ul = project(rig.left, pw);
      auto ur = project(rig.right, pw);
      ASSERT_TRUE(ul.ok() && ur.ok());
      auto p = triangulate_eq8<double>(l, r, *ul, *ur);
      ASSERT_TRUE(p.ok()) << p.error().message;
      worst = std::max(worst, (*p - pw).norm());
    }
    EXPECT_LT(worst, 1e-6) << "seed " << seed;  // mm, noise-free
  }
}

TEST(Triangulate, Eq8IsTheLeastSquaresPointForNoisyPixels) {
  // With 0.3 px noise the solution must still minimise the algebraic residual:
  // compare against a direct 4x3 least-squares solve (Eigen QR).
  const StereoRig rig = test::bumblebee_rig(4);
  const auto l = eq8_camera<double>(rig.left), r = eq8_camera<double>(rig.right);
  std::mt19937_64 rng(9);
  std::normal_distribution<double> n(0.0, 0.3);
  for (int i = 0; i < 100; ++i) {
    const Eigen::Vector3d pw = camera_to_world(rig.left, {50.0 * n(rng), 40.0 * n(rng), 700.0});
    const Eigen::Vector2d ul = *project(rig.left, pw) + Eigen::Vector2d(n(rng), n(rng));
    const Eigen::Vector2d ur = *project(rig.right, pw) + Eigen::Vector2d(n(rng), n(rng));
    Eigen::Matrix<double, 4, 3> a;
    Eigen::Vector4d b;
    int row = 0;
    for (const auto* cam : {&rig.left, &rig.right}) {
      const Eigen::Vector2d& uv = cam == &rig.left ? ul : ur;
      const Eigen::Vector2d xu = undistort_sensor(cam->kappa1, pixel_to_sensor(*cam, uv));
      for (int k = 0; k < 2; ++k) {
        a.row(row) = xu(k) * cam->R.row(2) - cam->f_mm * cam->R.row(k);
        b(row) = cam->f_mm * cam->T_mm(k) - xu(k) * cam->T_mm(2);
        ++row;
      }
    }
    const Eigen::Vector3d ref = a.colPivHouseholderQr().solve(b);
    auto p = triangulate_eq8<double>(l, r, ul, ur);
    ASSERT_TRUE(p.ok());
    EXPECT_LT((*p - ref).norm(), 1e-8);
    EXPECT_LT((*p - pw).norm(), 10.0);  // and near the true point
  }
}

TEST(Triangulate, ParallelRaysAreDegenerate) {
  StereoRig rig = test::bumblebee_rig(2);
  rig.right = rig.left;  // no baseline: both rays coincide
  const auto l = eq8_camera<double>(rig.left);
  auto p = triangulate_eq8<double>(l, l, {500.0, 400.0}, {500.0, 400.0});
  ASSERT_FALSE(p.ok());
  EXPECT_EQ(p.code(), Errc::degenerate);
}

struct DispMap {
  int w, h;
  std::vector<std::int16_t> q;
  Rect roi;
  DispMap(Rect r)
      : w(r.w), h(r.h), q(static_cast<std::size_t>(r.w) * r.h, kInvalidDisparity), roi(r) {}
  ConstDisparityMap view() const { return {ImageView<const std::int16_t>(q.data(), w, h), roi}; }
};

// The map's closed form (rectified_point) against the method's eq. 8 from the
// same correspondences mapped back to original pixels, on a rig with lens
// distortion, at full resolution and at a downsampling factor.
TEST(Triangulate, DisparityMapAgreesWithEq8ThroughTheOriginalCameras) {
  const StereoRig rig = test::bumblebee_rig(6, -0.004);
  auto pair = rectify_geometry(rig, 1024, 768);
  ASSERT_TRUE(pair.ok());
  const auto l = eq8_camera<double>(rig.left), r = eq8_camera<double>(rig.right);
  for (const int factor : {1, 4}) {
    DispMap m(Rect{400 / factor, 300 / factor, 40, 30});
    std::mt19937 rng(1);
    for (auto& q : m.q)
      q = static_cast<std::int16_t>(40 * 16 / factor + static_cast<int>(rng() % 400));
    m.q[5] = kInvalidDisparity;
    m.q[7] = 0;  // at infinity: rejected
    std::vector<Eigen::Vector3d> xyz(m.q.size());
    std::vector<PixelPos> px(m.q.size());
    test::HeapScope scope;
    auto stats = triangulate_disparity(*pair, m.view(), xyz, px, factor);
    EXPECT_EQ(scope.allocations(), 0u);
    ASSERT_TRUE(stats.ok()) << stats.error().message;
    EXPECT_EQ(stats->points, m.q.size() - 2);
    EXPECT_EQ(stats->rejected, 1u);
    double worst = 0;
    const double f = factor, centre = 0.5 * (factor - 1);
    for (std::size_t i = 0; i < stats->points; ++i) {
      const int x = px[i].u - m.roi.x, y = px[i].v - m.roi.y;
      const std::int16_t q = m.q[static_cast<std::size_t>(y) * m.w + x];
      const double u = px[i].u * f + centre, v = px[i].v * f + centre;
      auto ol = rectified_to_original(rig.left, pair->left, {u, v});
      auto orr = rectified_to_original(rig.right, pair->right, {u - disparity_px(q) * f, v});
      ASSERT_TRUE(ol.ok() && orr.ok());
      auto ref = triangulate_eq8<double>(l, r, *ol, *orr);
      ASSERT_TRUE(ref.ok());
      worst = std::max(worst, (*ref - xyz[i]).norm());
    }
    EXPECT_LT(worst, 1e-5) << "factor " << factor;  // mm, at about 1-4 m
  }
}

TEST(Triangulate, PointBudgetIsEnforced) {
  const StereoRig rig = test::bumblebee_rig(6);
  auto pair = rectify_geometry(rig, 1024, 768);
  ASSERT_TRUE(pair.ok());
  DispMap m(Rect{400, 300, 10, 10});
  for (auto& q : m.q) q = 50 * 16;
  std::vector<Eigen::Vector3d> xyz(99);
  std::vector<PixelPos> px(99);
  auto stats = triangulate_disparity(*pair, m.view(), xyz, px);
  ASSERT_FALSE(stats.ok());
  EXPECT_EQ(stats.code(), Errc::capacity_exceeded);
  EXPECT_NE(std::string(stats.error().message).find("budget 99"), std::string::npos);
}

}  // namespace
}  // namespace petra
