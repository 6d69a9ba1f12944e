// Epipolar geometry of a Tsai rig: F against projected points, the ray's
// image, ray meeting, and click transfer on a pair whose answer is known.
#include "algo/camera/epipolar.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>
#include <string>
#include <vector>

#include "tests/support/heap_counter.hpp"

namespace petra {
namespace {

TsaiCamera camera(double f, double kappa, double cx, double cy, double sx) {
  TsaiCamera c;
  c.width = 640;
  c.height = 480;
  c.f_mm = f;
  c.kappa1 = kappa;
  c.cx_px = cx;
  c.cy_px = cy;
  c.sx = sx;
  c.dx_mm = c.dy_mm = 0.006;
  return c;
}

// A rig with distortion, different intrinsics, a verged right camera and a
// world frame that is neither camera.
StereoRig verged_rig() {
  StereoRig rig;
  rig.left = camera(3.2, 0.02, 331.5, 243.0, 1.0);
  rig.right = camera(3.25, 0.023, 318.0, 251.5, 1.003);
  const Eigen::Matrix3d world = (Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX()) *
                                 Eigen::AngleAxisd(-0.2, Eigen::Vector3d::UnitZ()))
                                    .toRotationMatrix();
  rig.left.R = world;
  rig.left.T_mm = Eigen::Vector3d(10, -20, 300);
  const Eigen::Matrix3d rel =
      Eigen::AngleAxisd(0.03, Eigen::Vector3d(0.2, 1, 0.1).normalized()).toRotationMatrix();
  rig.right.R = rel * world;
  rig.right.T_mm = rel * rig.left.T_mm + Eigen::Vector3d(-60, 1, 2);
  return rig;
}

TEST(Epipolar, IdealAndDistortedPixelsAreInverse) {
  const TsaiCamera c = verged_rig().right;
  for (const Eigen::Vector2d& uv :
       {Eigen::Vector2d(0, 0), Eigen::Vector2d(639, 479), Eigen::Vector2d(100.25, 400.5)}) {
    auto back = distorted_pixel(c, ideal_pixel(c, uv));
    ASSERT_TRUE(back.ok());
    EXPECT_LT((*back - uv).norm(), 1e-9);
  }
  // Barrel distortion: ideal pixels lie further out than the real ones.
  EXPECT_GT((ideal_pixel(c, {0, 0}) - Eigen::Vector2d(c.cx_px, c.cy_px)).norm(),
            (Eigen::Vector2d(0, 0) - Eigen::Vector2d(c.cx_px, c.cy_px)).norm());
}

TEST(Epipolar, ProjectedPointsSatisfyTheFundamentalMatrix) {
  const StereoRig rig = verged_rig();
  auto f = fundamental_matrix(rig);
  ASSERT_TRUE(f.ok());
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  int tested = 0;
  double worst = 0;
  for (int k = 0; k < 200; ++k) {
    // A point in front of the left camera, 0.3-3 m away.
    const double z = 300 + 2700 * (0.5 + 0.5 * u(rng));
    const Eigen::Vector3d pc(0.4 * z * u(rng), 0.3 * z * u(rng), z);
    const Eigen::Vector3d pw = camera_to_world(rig.left, pc);
    auto l = project(rig.left, pw);
    auto r = project(rig.right, pw);
    if (!l || !r) continue;
    const Eigen::Vector3d line = epipolar_line(*f, ideal_pixel(rig.left, *l));
    worst = std::max(worst, std::abs(line.dot(ideal_pixel(rig.right, *r).homogeneous())));
    ++tested;
  }
  EXPECT_GT(tested, 150);
  EXPECT_LT(worst, 1e-8);  // distance from the epipolar line, ideal pixels
}

TEST(Epipolar, TheRaysImageRunsAlongTheLine) {
  const StereoRig rig = verged_rig();
  auto f = fundamental_matrix(rig);
  ASSERT_TRUE(f.ok());
  const Eigen::Vector2d click(250.0, 310.0);
  const Eigen::Vector3d line = epipolar_line(*f, ideal_pixel(rig.left, click));
  for (double depth : {200.0, 500.0, 1000.0, 5000.0}) {
    auto r = right_pixel_at_depth(rig, click, depth);
    ASSERT_TRUE(r.ok());
    EXPECT_LT(std::abs(line.dot(ideal_pixel(rig.right, *r).homogeneous())), 1e-8) << depth;
    // And the point at that depth is on the left pixel's ray.
    auto back = project(
        rig.left,
        camera_to_world(rig.left, depth * pixel_to_normalised(rig.left, click).homogeneous()));
    ASSERT_TRUE(back.ok());
    EXPECT_LT((*back - click).norm(), 1e-9);
  }
  EXPECT_EQ(right_pixel_at_depth(rig, click, 0).code(), Errc::non_positive);
}

TEST(Epipolar, RaysMeetAtTheirCommonPoint) {
  const Eigen::Vector3d p(10, 20, 500);
  const Ray a{Eigen::Vector3d(0, 0, 0), p.normalized()};
  const Ray b{Eigen::Vector3d(60, 0, 0), (p - Eigen::Vector3d(60, 0, 0)).normalized()};
  auto m = meet_rays(a, b);
  ASSERT_TRUE(m.ok());
  EXPECT_LT((m->point_mm - p).norm(), 1e-9);
  EXPECT_LT(m->gap_mm, 1e-9);
  // Skew rays: the midpoint of the common perpendicular and its length.
  const Ray c{Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0)};
  const Ray d{Eigen::Vector3d(0, 2, 5), Eigen::Vector3d(0, 0, 1)};
  m = meet_rays(c, d);
  ASSERT_TRUE(m.ok());
  EXPECT_LT((m->point_mm - Eigen::Vector3d(0, 1, 0)).norm(), 1e-12);
  EXPECT_NEAR(m->gap_mm, 2.0, 1e-12);
  EXPECT_EQ(meet_rays(c, Ray{Eigen::Vector3d(0, 1, 0), Eigen::Vector3d(1, 0, 0)}).code(),
            Errc::degenerate);
}

TEST(Epipolar, NoBaselineNoFundamentalMatrix) {
  StereoRig rig = verged_rig();
  rig.right.R = rig.left.R;
  rig.right.T_mm = rig.left.T_mm;
  EXPECT_EQ(fundamental_matrix(rig).code(), Errc::degenerate);
}

// A parallel, distortion-free rig 60 mm wide and a right image that is the
// left one shifted by 24 px: every click matches 24 px to the left, at
// depth f*B/d = (3.2/0.006 px) * 60 mm / 24 px = 1333.3 mm.
struct ShiftedPair {
  StereoRig rig;
  std::vector<std::uint8_t> left, right;
};

ShiftedPair shifted_pair() {
  ShiftedPair s;
  s.rig.left = camera(3.2, 0, 320, 240, 1);
  s.rig.right = s.rig.left;
  s.rig.right.T_mm = Eigen::Vector3d(-60, 0, 0);
  s.left.resize(640 * 480);
  s.right.resize(640 * 480);
  // Smooth random texture: sums of a few sinusoids with random phases.
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> ph(0, 6.283);
  double phase[6];
  for (double& p : phase) p = ph(rng);
  auto tex = [&](double x, double y) {
    return 128 + 40 * std::sin(0.21 * x + phase[0]) * std::sin(0.17 * y + phase[1]) +
           30 * std::sin(0.07 * x + 0.05 * y + phase[2]) +
           25 * std::sin(0.31 * x - 0.23 * y + phase[3]) +
           15 * std::sin(0.013 * x * y / 40 + phase[4]);
  };
  for (int y = 0; y < 480; ++y)
    for (int x = 0; x < 640; ++x) {
      s.left[static_cast<std::size_t>(y * 640 + x)] =
          static_cast<std::uint8_t>(std::lround(tex(x, y)));
      s.right[static_cast<std::size_t>(y * 640 + x)] =
          static_cast<std::uint8_t>(std::lround(tex(x + 24, y)));
    }
  return s;
}

TEST(Epipolar, ClickTransferFindsTheShiftWithoutHeap) {
  const ShiftedPair s = shifted_pair();
  const ConstGray8View l(s.left.data(), 640, 480), r(s.right.data(), 640, 480);
  for (const Eigen::Vector2d& click :
       {Eigen::Vector2d(300, 200), Eigen::Vector2d(100.5, 400.25), Eigen::Vector2d(600, 50)}) {
    Result<ClickMatch> m = Error::make(Errc::not_ready, "not run");
    {
      test::HeapScope scope;
      m = transfer_click(s.rig, l, r, click, ClickOptions{});
      EXPECT_EQ(scope.allocations(), 0u);
    }
    ASSERT_TRUE(m.ok()) << m.error().message;
    EXPECT_LT((m->right_px - (click - Eigen::Vector2d(24, 0))).norm(), 0.05) << click.transpose();
    EXPECT_GT(m->score, 0.99);
    EXPECT_NEAR(m->depth_mm, 3.2 / 0.006 * 60 / 24, 3.0);  // 0.05 px of 24 is 0.2 %
    EXPECT_LT(m->ray_gap_mm, 1e-6);
  }
}

TEST(Epipolar, ClickTransferRefusesWhatItCannotDo) {
  const ShiftedPair s = shifted_pair();
  const ConstGray8View l(s.left.data(), 640, 480), r(s.right.data(), 640, 480);
  auto m = transfer_click(s.rig, l, r, {3, 200}, {});
  ASSERT_FALSE(m.ok());
  EXPECT_EQ(m.code(), Errc::out_of_range);
  std::vector<std::uint8_t> flat(640 * 480, 90);
  m = transfer_click(s.rig, ConstGray8View(flat.data(), 640, 480), r, {300, 200}, {});
  ASSERT_FALSE(m.ok());
  EXPECT_NE(std::string(m.error().message).find("no texture"), std::string::npos)
      << m.error().message;
  m = transfer_click(s.rig, ConstGray8View(s.left.data(), 320, 240), r, {100, 100}, {});
  ASSERT_FALSE(m.ok());
  EXPECT_NE(std::string(m.error().message).find("left image 320x240"), std::string::npos)
      << m.error().message;
  ClickOptions wide;
  wide.half_window = kMaxClickHalfWindow + 1;
  EXPECT_EQ(transfer_click(s.rig, l, r, {300, 200}, wide).code(), Errc::invalid_argument);
}

}  // namespace
}  // namespace petra
