// Stereo calibration on corners projected through a known Tsai rig, with and
// without detection noise, and the inputs it must refuse.
#include "sim/calib/stereo_calibration.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>
#include <string>

#include "tests/sim/calib/calib_test_scenes.hpp"

namespace petra::calib {
namespace {

using test::BoardPose;
using test::kDeg;
using test::kPoses;
using test::observe;

StereoCalibOptions options_for(const StereoRig& rig, const BoardSpec& b) {
  StereoCalibOptions o;
  o.cols = b.cols;
  o.rows = b.rows;
  o.square_mm = b.square_mm;
  for (TsaiCamera* s : {&o.left_sensor, &o.right_sensor}) {
    s->width = rig.left.width;
    s->height = rig.left.height;
    s->dx_mm = rig.left.dx_mm;
    s->dy_mm = rig.left.dy_mm;
  }
  return o;
}

double angle_deg(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  return Eigen::AngleAxisd(a * b.transpose()).angle() / kDeg;
}

std::vector<StereoPairCorners> observe_all(const StereoRig& rig, const BoardSpec& b,
                                           double noise_px) {
  std::mt19937_64 rng(2024);
  std::vector<StereoPairCorners> pairs;
  for (const BoardPose& p : kPoses) pairs.push_back(observe(rig, b, p, noise_px, rng));
  return pairs;
}

TEST(StereoCalibration, ExactCornersGiveTheRigBack) {
  const StereoRig truth = test::sample_rig();
  const BoardSpec board;
  auto cal = calibrate_stereo(observe_all(truth, board, 0.0), options_for(truth, board));
  ASSERT_TRUE(cal.ok()) << cal.error().message;
  for (int side = 0; side < 2; ++side) {
    const TsaiCamera& t = side == 0 ? truth.left : truth.right;
    const TsaiCamera& c = side == 0 ? cal->rig.left : cal->rig.right;
    EXPECT_NEAR(c.f_mm, t.f_mm, 1e-7 * t.f_mm);
    EXPECT_NEAR(c.kappa1, t.kappa1, 1e-6 * t.kappa1);
    EXPECT_NEAR(c.cx_px, t.cx_px, 1e-5);
    EXPECT_NEAR(c.cy_px, t.cy_px, 1e-5);
    EXPECT_NEAR(c.sx, t.sx, 1e-8);
    EXPECT_LT(angle_deg(c.R, t.R), 1e-6);
    EXPECT_LT((c.T_mm - t.T_mm).norm(), 1e-5);
  }
  EXPECT_LT(cal->rms_px, 1e-6);
  EXPECT_NEAR(cal->baseline_mm, (camera_centre_world(truth.right)).norm(), 1e-5);
}

TEST(StereoCalibration, NoisyCornersGiveTheRigWithinTheStatedTolerances) {
  // 0.1 px of Gaussian noise per coordinate: what sub-pixel detection achieves
  // on sharp boards (the OpenCV set fits to 0.21-0.25 px RMS, which includes
  // lens effects the model lacks). With 12 views of a 9x6 board the fit itself
  // reports one-sigma uncertainties of about f 0.003 mm (0.1 %), kappa1 3e-4
  // /mm^2 (1.5 %), cx, cy 0.7 px, sx 2e-4; the rig rotation follows the
  // principal points (0.7 px / 533 px = 0.075 deg). The tolerances are four
  // sigma, so they scale with the noise: f 0.4 %, kappa1 6 %, cx, cy 3 px,
  // sx 0.001, rotation 0.3 deg, right camera centre 0.5 mm (0.8 % of 60 mm).
  const StereoRig truth = test::sample_rig();
  const BoardSpec board;
  auto cal = calibrate_stereo(observe_all(truth, board, 0.1), options_for(truth, board));
  ASSERT_TRUE(cal.ok()) << cal.error().message;
  // The residual matches the noise: 0.1 px per coordinate is 0.141 px per corner.
  EXPECT_NEAR(cal->rms_px, 0.1 * std::sqrt(2.0), 0.015);
  for (int side = 0; side < 2; ++side) {
    const TsaiCamera& t = side == 0 ? truth.left : truth.right;
    const TsaiCamera& c = side == 0 ? cal->rig.left : cal->rig.right;
    const auto& s = side == 0 ? cal->left_sigma : cal->right_sigma;
    std::printf(
        "%s: f %.5f (err %.2g, sigma %.2g) kappa1 %.5f (err %.2g, sigma %.2g) cx err %.3f (sigma "
        "%.3f) "
        "cy err %.3f (sigma %.3f) sx err %.2g (sigma %.2g)\n",
        side == 0 ? "left" : "right", c.f_mm, c.f_mm - t.f_mm, s[kF], c.kappa1, c.kappa1 - t.kappa1,
        s[kKappa1], c.cx_px - t.cx_px, s[kCx], c.cy_px - t.cy_px, s[kCy], c.sx - t.sx, s[kSx]);
    EXPECT_NEAR(c.f_mm, t.f_mm, 4e-3 * t.f_mm);
    EXPECT_NEAR(c.kappa1, t.kappa1, 0.06 * t.kappa1);
    EXPECT_NEAR(c.cx_px, t.cx_px, 3.0);
    EXPECT_NEAR(c.cy_px, t.cy_px, 3.0);
    EXPECT_NEAR(c.sx, t.sx, 1e-3);
    // And the reported uncertainties are honest: errors within 4 sigma.
    EXPECT_LT(std::abs(c.f_mm - t.f_mm), 4 * s[kF]);
    EXPECT_LT(std::abs(c.kappa1 - t.kappa1), 4 * s[kKappa1]);
    EXPECT_LT(std::abs(c.cx_px - t.cx_px), 4 * s[kCx]);
    EXPECT_LT(std::abs(c.cy_px - t.cy_px), 4 * s[kCy]);
    EXPECT_LT(std::abs(c.sx - t.sx), 4 * s[kSx]);
  }
  EXPECT_LT(angle_deg(cal->rig.right.R, truth.right.R), 0.3);
  const Eigen::Vector3d centre = camera_centre_world(cal->rig.right);
  const Eigen::Vector3d true_centre = camera_centre_world(truth.right);
  std::printf("right centre error %.3f mm, baseline %.3f (true %.3f) mm, rotation error %.4f deg\n",
              (centre - true_centre).norm(), cal->baseline_mm, true_centre.norm(),
              angle_deg(cal->rig.right.R, truth.right.R));
  EXPECT_LT((centre - true_centre).norm(), 0.5);
  // The world frame is the left camera.
  EXPECT_TRUE(cal->rig.left.R.isIdentity(0));
  EXPECT_TRUE(cal->rig.left.T_mm.isZero(0));
}

TEST(StereoCalibration, WorldOnTheTargetIsTheFirstBoard) {
  const StereoRig truth = test::sample_rig();
  const BoardSpec board;
  StereoCalibOptions o = options_for(truth, board);
  o.world_at_target = true;
  const std::vector<StereoPairCorners> pairs = observe_all(truth, board, 0.0);
  auto cal = calibrate_stereo(pairs, o);
  ASSERT_TRUE(cal.ok()) << cal.error().message;
  EXPECT_EQ(cal->world_pair, 0);
  // Board corners (world points now) project onto the observed corners of pair 0.
  for (int k : {0, 8, 45, 53}) {
    const Eigen::Vector3d pw = board_corner(board, k % 9, k / 9);
    auto l = project(cal->rig.left, pw);
    auto r = project(cal->rig.right, pw);
    ASSERT_TRUE(l.ok() && r.ok());
    EXPECT_LT((*l - pairs[0].left_uv[static_cast<std::size_t>(k)]).norm(), 1e-5);
    EXPECT_LT((*r - pairs[0].right_uv[static_cast<std::size_t>(k)]).norm(), 1e-5);
  }
  EXPECT_NEAR(cal->baseline_mm, camera_centre_world(truth.right).norm(), 1e-5);
}

TEST(StereoCalibration, FewerThanThreeViewsAreRefused) {
  const StereoRig truth = test::sample_rig();
  const BoardSpec board;
  std::vector<StereoPairCorners> pairs = observe_all(truth, board, 0.05);
  pairs.resize(2);
  auto cal = calibrate_stereo(pairs, options_for(truth, board));
  ASSERT_FALSE(cal.ok());
  EXPECT_NE(std::string(cal.error().message).find("need at least 3"), std::string::npos)
      << cal.error().message;
  // Three views per camera, but only two with the board in both images.
  pairs = observe_all(truth, board, 0.05);
  pairs.resize(4);
  pairs[0].right_uv.clear();
  pairs[1].left_uv.clear();
  cal = calibrate_stereo(pairs, options_for(truth, board));
  ASSERT_FALSE(cal.ok());
  EXPECT_NE(std::string(cal.error().message).find("both images of 2 usable pairs"),
            std::string::npos)
      << cal.error().message;
}

TEST(StereoCalibration, FrontoParallelViewsAreRefused) {
  const StereoRig truth = test::sample_rig();
  const BoardSpec board;
  std::mt19937_64 rng(5);
  std::vector<StereoPairCorners> pairs;
  for (int k = 0; k < 6; ++k)
    pairs.push_back(
        observe(truth, board, {0.5 * (k % 2), 0.0, 30.0 * k, 450.0 + 20 * k, 30, 0}, 0.05, rng));
  auto cal = calibrate_stereo(pairs, options_for(truth, board));
  ASSERT_FALSE(cal.ok());
  EXPECT_NE(std::string(cal.error().message).find("no view tilted enough"), std::string::npos)
      << cal.error().message;
}

TEST(StereoCalibration, DuplicatedViewsCountOnce) {
  const StereoRig truth = test::sample_rig();
  const BoardSpec board;
  std::vector<StereoPairCorners> all = observe_all(truth, board, 0.05);
  // Two distinct board positions, each photographed three times.
  std::vector<StereoPairCorners> pairs;
  for (int k = 0; k < 6; ++k) {
    pairs.push_back(all[static_cast<std::size_t>(k % 2)]);
    pairs.back().left_name = "left0" + std::to_string(k);
  }
  auto cal = calibrate_stereo(pairs, options_for(truth, board));
  ASSERT_FALSE(cal.ok());
  EXPECT_NE(std::string(cal.error().message).find("2 distinct views"), std::string::npos)
      << cal.error().message;
  // With enough distinct views, a duplicate is noted and left out.
  all.push_back(all[3]);
  all.back().left_name = "left-again";
  cal = calibrate_stereo(all, options_for(truth, board));
  ASSERT_TRUE(cal.ok()) << cal.error().message;
  bool noted = false;
  for (const std::string& n : cal->notes)
    noted |= n.find("left-again: same board position") != std::string::npos;
  EXPECT_TRUE(noted);
}

TEST(StereoCalibration, CornerCountMustMatchTheBoard) {
  const StereoRig truth = test::sample_rig();
  const BoardSpec board;
  std::vector<StereoPairCorners> pairs = observe_all(truth, board, 0.0);
  pairs[2].left_uv.pop_back();
  auto cal = calibrate_stereo(pairs, options_for(truth, board));
  ASSERT_FALSE(cal.ok());
  EXPECT_EQ(cal.code(), Errc::invalid_argument);
}

}  // namespace
}  // namespace petra::calib
