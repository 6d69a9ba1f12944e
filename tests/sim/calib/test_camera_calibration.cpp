// One camera from several board views: what the views do not determine is
// fixed, with a note, instead of being fitted to noise.
#include "sim/calib/camera_calibration.hpp"

#include <gtest/gtest.h>

#include <random>
#include <string>

#include "tests/sim/calib/calib_test_scenes.hpp"

namespace petra::calib {
namespace {

std::vector<PlanarView> views_at(const std::vector<test::BoardPose>& poses, double noise_px) {
  const BoardSpec b;
  std::mt19937_64 rng(1);
  std::normal_distribution<double> noise(0, noise_px);
  std::vector<PlanarView> views;
  for (const test::BoardPose& p : poses) {
    TsaiCamera cam = test::sample_camera();
    test::place_board(cam, b, p.ax, p.ay, p.az, p.distance, p.shift_x, p.shift_y);
    PlanarView v;
    for (int j = 0; j < b.rows; ++j)
      for (int i = 0; i < b.cols; ++i) {
        auto q = project(cam, board_corner(b, i, j));
        EXPECT_TRUE(q.ok());
        v.board_mm.emplace_back(i * b.square_mm, j * b.square_mm);
        v.uv_px.push_back(*q + Eigen::Vector2d(noise(rng), noise(rng)));
      }
    views.push_back(v);
  }
  return views;
}

TEST(CameraCalibration, ParallelBoardsLeaveSxUndeterminedSoItIsFixed) {
  // Five views of the board, all tilted 25 degrees about the same axis and
  // only moved: parallel planes give too few constraints for sx.
  const std::vector<test::BoardPose> parallel = {{25, 0, 0, 500, 20, 0},
                                                 {25, 0, 0, 450, -30, 10},
                                                 {25, 0, 0, 600, 40, -20},
                                                 {25, 0, 0, 520, 0, 30},
                                                 {25, 0, 0, 480, 10, -10}};
  auto c = calibrate_camera(views_at(parallel, 0.1), test::sample_camera());
  ASSERT_TRUE(c.ok()) << c.error().message;
  EXPECT_FALSE(c->estimated.sx);
  EXPECT_EQ(c->camera.sx, 1.0);
  ASSERT_FALSE(c->notes.empty());
  EXPECT_NE(c->notes[0].find("sx not determined by these views"), std::string::npos) << c->notes[0];
  // Turned in their plane and tilted both ways, the same number of views do.
  const std::vector<test::BoardPose> varied = {{25, 0, 0, 500, 20, 0},
                                               {-25, 0, 0, 450, -30, 10},
                                               {35, 0, 0, 600, 40, -20},
                                               {-15, 0, 90, 520, 0, 30},
                                               {20, 0, 180, 480, 10, -10}};
  c = calibrate_camera(views_at(varied, 0.1), test::sample_camera());
  ASSERT_TRUE(c.ok()) << c.error().message;
  EXPECT_TRUE(c->estimated.sx && c->estimated.centre);
  EXPECT_TRUE(c->notes.empty());
}

TEST(CameraCalibration, FixedCentreStaysAtTheImageCentre) {
  CameraCalibOptions o;
  o.estimate_centre = false;
  o.estimate_sx = false;
  auto c = calibrate_camera(
      views_at({{25, 0, 0, 500, 20, 0}, {-25, 10, 0, 450, -30, 10}, {0, 30, 45, 600, 40, -20}},
               0.0),
      test::sample_camera(), o);
  ASSERT_TRUE(c.ok()) << c.error().message;
  EXPECT_EQ(c->camera.cx_px, 319.5);
  EXPECT_EQ(c->camera.cy_px, 239.5);
  EXPECT_EQ(c->sigma[kCx], 0.0);
  // The true centre is 12 px away, so exact corners no longer fit exactly
  // (the poses absorb most of it: 0.08 px).
  EXPECT_GT(c->rms_px, 0.01);
}

}  // namespace
}  // namespace petra::calib
