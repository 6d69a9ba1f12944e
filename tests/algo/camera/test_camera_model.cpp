#include "algo/camera/camera_model.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>

namespace petra {
namespace {

TsaiCamera simple_camera() {
  TsaiCamera c;
  c.width = 640;
  c.height = 480;
  c.f_mm = 4.0;
  c.dx_mm = 0.005;
  c.dy_mm = 0.005;
  c.sx = 1.0;
  c.cx_px = 320;
  c.cy_px = 240;
  return c;
}

// A Bumblebee2-like camera, tilted and displaced, with barrel distortion.
TsaiCamera rig_camera(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  TsaiCamera c;
  c.width = 1024;
  c.height = 768;
  c.f_mm = 3.8 + 0.1 * u(rng);
  c.dx_mm = 0.00465;
  c.dy_mm = 0.00465;
  c.sx = 1.0 + 0.01 * u(rng);
  c.cx_px = 512 + 10 * u(rng);
  c.cy_px = 384 + 10 * u(rng);
  c.kappa1 = 0.02 * u(rng);
  c.R = (Eigen::AngleAxisd(0.6 * u(rng), Eigen::Vector3d::UnitX()) *
         Eigen::AngleAxisd(0.3 * u(rng), Eigen::Vector3d::UnitY()) *
         Eigen::AngleAxisd(0.3 * u(rng), Eigen::Vector3d::UnitZ()))
            .toRotationMatrix();
  c.T_mm = Eigen::Vector3d(100 * u(rng), 100 * u(rng), 100 * u(rng));
  return c;
}

TEST(CameraModel, HandWorkedProjectionWithoutDistortion) {
  const TsaiCamera c = simple_camera();
  // Xu = 4*100/1000 = 0.4 mm -> u = 0.4/0.005 + 320 = 400; Yu = 0.2 mm -> v = 280.
  auto uv = project(c, {100, 50, 1000});
  ASSERT_TRUE(uv.ok());
  EXPECT_NEAR(uv->x(), 400.0, 1e-12);
  EXPECT_NEAR(uv->y(), 280.0, 1e-12);
}

TEST(CameraModel, HandWorkedProjectionWithTranslationAndScale) {
  TsaiCamera c = simple_camera();
  c.T_mm = {0, 0, 500};
  c.sx = 1.02;
  // Pc = (100, 50, 1000); u = 1.02*0.4/0.005 + 320 = 401.6.
  auto uv = project(c, {100, 50, 500});
  ASSERT_TRUE(uv.ok());
  EXPECT_NEAR(uv->x(), 401.6, 1e-12);
  EXPECT_NEAR(uv->y(), 280.0, 1e-12);
}

TEST(CameraModel, HandWorkedProjectionWithDistortion) {
  TsaiCamera c = simple_camera();
  c.kappa1 = 0.01;
  // Xd = 1 mm, Yd = 0: r^2 = 1, Xu = 1.01 mm, so Xc/Zc = 1.01/4.
  // u = 1/0.005 + 320 = 520, v = 240.
  auto uv = project(c, {252.5, 0, 1000});
  ASSERT_TRUE(uv.ok());
  EXPECT_NEAR(uv->x(), 520.0, 1e-9);
  EXPECT_NEAR(uv->y(), 240.0, 1e-9);
  // And back: pixel (520, 240) views along (1.01/4, 0, 1).
  const Ray ray = pixel_to_ray(c, {520, 240});
  EXPECT_NEAR(ray.direction.x() / ray.direction.z(), 1.01 / 4.0, 1e-15);
}

TEST(CameraModel, DistortionInverseAccuracy) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> k(-0.03, 0.03), p(-2.5, 2.5);
  int solved = 0;
  for (int i = 0; i < 20000; ++i) {
    const double kappa = k(rng);
    const Eigen::Vector2d pu(p(rng), p(rng));
    auto pd = distort_sensor(kappa, pu);
    if (!pd) {
      EXPECT_LT(kappa, 0.0);
      EXPECT_EQ(pd.code(), Errc::no_solution);
      continue;
    }
    ++solved;
    const double rd = pd->norm();
    EXPECT_LE(std::abs(rd * (1 + kappa * rd * rd) - pu.norm()), 1e-12);
    EXPECT_LE((undistort_sensor(kappa, *pd) - pu).norm(), 1e-12);
    // Stays on the monotonic branch of the model.
    EXPECT_GT(1.0 + 3.0 * kappa * rd * rd, 0.0);
  }
  EXPECT_GT(solved, 15000);
}

TEST(CameraModel, RoundTripWorldPixelRay) {
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int checked = 0;
  for (int n = 0; n < 200; ++n) {
    const TsaiCamera c = rig_camera(rng);
    ASSERT_TRUE(validate(c).ok()) << validate(c).error().message;
    for (int i = 0; i < 50; ++i) {
      // A point in front of the camera that it images: from a pixel's
      // undistorted direction, at a random depth (not through pixel_to_ray,
      // which is under test).
      const Eigen::Vector2d px(c.width * (0.5 + 0.5 * u(rng)), c.height * (0.5 + 0.5 * u(rng)));
      const Eigen::Vector2d pu = undistort_sensor(c.kappa1, pixel_to_sensor(c, px));
      const double z = 600 + 300 * u(rng);
      const Eigen::Vector3d pw =
          camera_to_world(c, Eigen::Vector3d(pu.x(), pu.y(), c.f_mm) * (z / c.f_mm));
      auto uv = project(c, pw);
      ASSERT_TRUE(uv.ok());
      const Ray ray = pixel_to_ray(c, *uv);
      const Eigen::Vector3d to_point = pw - ray.origin_mm;
      const double off_ray = (to_point - to_point.dot(ray.direction) * ray.direction).norm();
      EXPECT_LE(off_ray, 1e-9 * to_point.norm());
      EXPECT_GT(to_point.dot(ray.direction), 0.0);
      ++checked;
    }
  }
  EXPECT_EQ(checked, 10000);
}

TEST(CameraModel, PointBehindCameraIsRefused) {
  const TsaiCamera c = simple_camera();
  EXPECT_EQ(project(c, {0, 0, -10}).code(), Errc::out_of_range);
  EXPECT_EQ(project(c, {0, 0, 0}).code(), Errc::out_of_range);
}

TEST(CameraModel, ValidateRejectsBadFields) {
  TsaiCamera c = simple_camera();
  EXPECT_TRUE(validate(c).ok());
  auto bad = [&](auto mutate, Errc code) {
    TsaiCamera d = simple_camera();
    mutate(d);
    EXPECT_EQ(validate(d).code(), code);
  };
  bad([](TsaiCamera& d) { d.f_mm = 0; }, Errc::non_positive);
  bad([](TsaiCamera& d) { d.dx_mm = -1; }, Errc::non_positive);
  bad([](TsaiCamera& d) { d.dy_mm = 0; }, Errc::non_positive);
  bad([](TsaiCamera& d) { d.sx = 0; }, Errc::non_positive);
  bad([](TsaiCamera& d) { d.width = 0; }, Errc::non_positive);
  bad([](TsaiCamera& d) { d.R(0, 1) = 0.1; }, Errc::not_orthonormal);
  bad([](TsaiCamera& d) { d.R(2, 2) = -1; }, Errc::not_orthonormal);
  bad([](TsaiCamera& d) { d.T_mm.x() = std::nan(""); }, Errc::invalid_argument);
  // Corner radius ~2 mm: kappa1 = -0.2 folds the image.
  bad([](TsaiCamera& d) { d.kappa1 = -0.2; }, Errc::invalid_argument);
}

TEST(CameraModel, PinholeConversionWithoutDistortionIsExact) {
  std::mt19937_64 rng(3);
  TsaiCamera c = rig_camera(rng);
  c.kappa1 = 0;
  const PinholeConversion p = to_pinhole(c);
  EXPECT_EQ(p.pinhole.k1, 0.0);
  EXPECT_LT(p.max_error_px, 1e-9);
  const TsaiConversion back = from_pinhole(p.pinhole, c.dy_mm);
  EXPECT_NEAR(back.camera.f_mm, c.f_mm, 1e-12);
  EXPECT_NEAR(back.camera.sx, c.sx, 1e-12);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i < 100; ++i) {
    const Eigen::Vector3d pw = camera_to_world(c, {200 * u(rng), 150 * u(rng), 800});
    const Eigen::Vector2d a = *project(c, pw);
    EXPECT_LT((project_pinhole(p.pinhole, pw) - a).norm(), 1e-9);
    EXPECT_LT((*project(back.camera, pw) - a).norm(), 1e-9);
  }
}

TEST(CameraModel, PinholeConversionWithDistortionIsCloseAndBounded) {
  std::mt19937_64 rng(5);
  TsaiCamera c = rig_camera(rng);
  // Tsai's kappa1 maps distorted to undistorted, OpenCV's k1 the other way:
  // kappa1 < 0 is pincushion, k1 > 0. Corner distortion here is about 2.7 %.
  c.kappa1 = -0.003;
  const PinholeConversion p = to_pinhole(c);
  EXPECT_GT(p.pinhole.k1, 0.0);
  // First-order relation of the two radial models: k1 ~ -kappa1 * f^2.
  EXPECT_NEAR(p.pinhole.k1, -c.kappa1 * c.f_mm * c.f_mm, 0.1 * std::abs(p.pinhole.k1));
  EXPECT_LT(p.max_error_px, 0.5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i < 200; ++i) {
    const Eigen::Vector3d pw = camera_to_world(c, {250 * u(rng), 180 * u(rng), 800});
    const Eigen::Vector2d a = *project(c, pw);
    if (a.x() < 0 || a.y() < 0 || a.x() > c.width - 1 || a.y() > c.height - 1) continue;
    EXPECT_LE((project_pinhole(p.pinhole, pw) - a).norm(), p.max_error_px + 1e-6);
  }
  const TsaiConversion back = from_pinhole(p.pinhole, c.dy_mm);
  EXPECT_NEAR(back.camera.kappa1, c.kappa1, 0.1 * std::abs(c.kappa1));
}

}  // namespace
}  // namespace petra
