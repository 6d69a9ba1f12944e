// Shared synthetic scenes for the calibration tests: a camera like the one of
// OpenCV's stereo sample set (640x480, fx about 533 px, barrel distortion of
// about 10 % in the corners), a stereo rig of two such cameras 60 mm apart,
// and board poses seen from the front by both.
#pragma once

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>
#include <vector>

#include "algo/camera/camera_model.hpp"
#include "sim/calib/board_renderer.hpp"
#include "sim/calib/stereo_calibration.hpp"

namespace petra::calib::test {

inline TsaiCamera sample_camera() {
  TsaiCamera c;
  c.width = 640;
  c.height = 480;
  c.f_mm = 3.2;
  c.dx_mm = 0.006;
  c.dy_mm = 0.006;
  c.sx = 1.0;
  c.kappa1 = 0.02;
  c.cx_px = 331.5;
  c.cy_px = 243.0;
  return c;
}

// Board pose: rotations about the board's x, y, z axes (degrees), the board's
// centre on the optical axis at distance_mm, then shifted in the image plane.
inline void place_board(TsaiCamera& cam, const BoardSpec& b, double ax_deg, double ay_deg,
                        double az_deg, double distance_mm, double shift_x_mm = 0,
                        double shift_y_mm = 0) {
  const double d = 3.14159265358979323846 / 180.0;
  const Eigen::Matrix3d r = (Eigen::AngleAxisd(ax_deg * d, Eigen::Vector3d::UnitX()) *
                             Eigen::AngleAxisd(ay_deg * d, Eigen::Vector3d::UnitY()) *
                             Eigen::AngleAxisd(az_deg * d, Eigen::Vector3d::UnitZ()))
                                .toRotationMatrix();
  const Eigen::Vector3d centre((b.cols - 1) * b.square_mm / 2, (b.rows - 1) * b.square_mm / 2, 0);
  cam.R = r;
  cam.T_mm = Eigen::Vector3d(shift_x_mm, shift_y_mm, distance_mm) - r * centre;
}

inline constexpr double kDeg = 3.14159265358979323846 / 180.0;

// The left camera at the world origin, the right one 60 mm to its right,
// turned by about 1.5 degrees, with its own intrinsics.
inline StereoRig sample_rig() {
  StereoRig rig;
  rig.left = sample_camera();
  rig.right = sample_camera();
  rig.right.f_mm = 3.25;
  rig.right.kappa1 = 0.023;
  rig.right.cx_px = 318.0;
  rig.right.cy_px = 251.5;
  rig.right.sx = 1.003;
  rig.right.R = (Eigen::AngleAxisd(1.2 * kDeg, Eigen::Vector3d::UnitY()) *
                 Eigen::AngleAxisd(-0.6 * kDeg, Eigen::Vector3d::UnitX()) *
                 Eigen::AngleAxisd(0.4 * kDeg, Eigen::Vector3d::UnitZ()))
                    .toRotationMatrix();
  rig.right.T_mm = -rig.right.R * Eigen::Vector3d(60.0, 0.8, -1.5);  // centre at (60, 0.8, -1.5)
  return rig;
}

struct BoardPose {
  double ax, ay, az, distance, shift_x, shift_y;
};

// Tilts of 15-40 degrees about both axes, the board turned in its plane,
// moved around the field of view: what a careful operator collects.
inline const BoardPose kPoses[] = {
    {25, 0, 0, 500, 20, 0},      {-25, 0, 10, 520, 30, 10},    {0, 30, -5, 480, 20, -20},
    {0, -30, 5, 500, 40, 15},    {20, 20, 90, 560, 30, 0},     {-20, -25, 180, 540, 30, 5},
    {30, -15, 30, 600, -20, 40}, {-15, 35, -20, 580, 70, -30}, {35, 10, 150, 620, 30, -40},
    {10, -35, 60, 550, -10, 30}, {-35, -10, 270, 600, 60, 20}, {15, 15, 200, 460, 30, 0},
};

// The camera `side` (0 left, 1 right) of the rig with R, T set to the pose
// of the board (board -> camera) for board pose p, given relative to the left camera.
inline TsaiCamera camera_seeing(const StereoRig& rig, int side, const BoardSpec& b,
                                const BoardPose& p) {
  TsaiCamera board_in_left = rig.left;
  place_board(board_in_left, b, p.ax, p.ay, p.az, p.distance, p.shift_x, p.shift_y);
  TsaiCamera cam = side == 0 ? rig.left : rig.right;
  // board -> camera = (world -> camera) * (board -> world); world = left camera.
  cam.T_mm = cam.R * board_in_left.T_mm + cam.T_mm;
  cam.R = cam.R * board_in_left.R;
  return cam;
}

// Corners of the board in pose p seen by both cameras, plus Gaussian noise.
inline StereoPairCorners observe(const StereoRig& rig, const BoardSpec& b, const BoardPose& p,
                                 double noise_px, std::mt19937_64& rng) {
  std::normal_distribution<double> noise(0.0, noise_px > 0 ? noise_px : 1.0);
  StereoPairCorners pc;
  for (int side = 0; side < 2; ++side) {
    const TsaiCamera cam = camera_seeing(rig, side, b, p);
    std::vector<Eigen::Vector2d>& uv = side == 0 ? pc.left_uv : pc.right_uv;
    for (int j = 0; j < b.rows; ++j)
      for (int i = 0; i < b.cols; ++i) {
        auto q = project(cam, board_corner(b, i, j));
        EXPECT_TRUE(q.ok());
        EXPECT_TRUE(q->x() > 0 && q->y() > 0 && q->x() < cam.width - 1 && q->y() < cam.height - 1)
            << "corner outside the image: pose " << p.ax << "," << p.ay << "," << p.az;
        uv.push_back(*q + (noise_px > 0 ? Eigen::Vector2d(noise(rng), noise(rng))
                                        : Eigen::Vector2d::Zero()));
      }
  }
  pc.left_name = "left";
  pc.right_name = "right";
  return pc;
}

}  // namespace petra::calib::test
