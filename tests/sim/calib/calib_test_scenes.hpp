// Shared synthetic scenes for the calibration tests: a camera like the one of
// OpenCV's stereo sample set (640x480, fx about 533 px, barrel distortion of
// about 10 % in the corners) and board poses seen from the front.
#pragma once

#include <Eigen/Geometry>

#include "algo/camera_model.hpp"
#include "sim/calib/board_renderer.hpp"

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

}  // namespace petra::calib::test
