// Tsai's radial-alignment camera model with one radial coefficient (the
// calib.json contract, docs/icd.md). Lengths in millimetres, pixels in pixels.
//   Pc = R*Pw + T                       (camera z forward)
//   Xu = f*Xc/Zc,  Yu = f*Yc/Zc         (undistorted sensor coordinates, mm)
//   Xu = Xd*(1 + kappa1*r^2), Yu = Yd*(1 + kappa1*r^2), r^2 = Xd^2 + Yd^2
//   u = sx*Xd/dx + cx,  v = Yd/dy + cy  (pixel (i,j) has its centre at (i,j))
#pragma once

#include <Eigen/Core>

#include "algo/core/result.hpp"

namespace petra {

struct TsaiCamera {
  int width = 0;  // image size, px
  int height = 0;
  double f_mm = 0;    // effective focal length
  double kappa1 = 0;  // radial distortion, 1/mm^2
  double sx = 1;      // horizontal scale factor (uncertainty in x sampling)
  double cx_px = 0;   // principal point
  double cy_px = 0;
  double dx_mm = 0;  // pixel pitch
  double dy_mm = 0;
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();  // world -> camera rotation
  Eigen::Vector3d T_mm = Eigen::Vector3d::Zero();   // world -> camera translation
};

struct StereoRig {
  TsaiCamera left;
  TsaiCamera right;
};

// A viewing ray in the world frame; direction has unit length.
struct Ray {
  Eigen::Vector3d origin_mm;
  Eigen::Vector3d direction;
};

// Inverse of the radial model: the distorted sensor point whose undistorted
// image is (Xu, Yu). Newton iteration on the radius, monotone from r = |Pu|;
// converges to |r_d(1+k r_d^2) - r_u| <= 1e-12 mm (tested). Fails when
// kappa1 < 0 and r_u lies beyond the model's fold, where no solution exists.
Result<Eigen::Vector2d> distort_sensor(double kappa1, const Eigen::Vector2d& undistorted_mm);
// Forward radial model: distorted sensor point -> undistorted (closed form).
Eigen::Vector2d undistort_sensor(double kappa1, const Eigen::Vector2d& distorted_mm);

Eigen::Vector3d world_to_camera(const TsaiCamera& cam, const Eigen::Vector3d& pw_mm);
Eigen::Vector3d camera_to_world(const TsaiCamera& cam, const Eigen::Vector3d& pc_mm);
Eigen::Vector3d camera_centre_world(const TsaiCamera& cam);

// Pixel <-> distorted sensor coordinates (mm).
Eigen::Vector2d pixel_to_sensor(const TsaiCamera& cam, const Eigen::Vector2d& uv_px);
Eigen::Vector2d sensor_to_pixel(const TsaiCamera& cam, const Eigen::Vector2d& distorted_mm);

// World point -> pixel. Fails for points at or behind the camera plane and
// where the distortion inverse has no solution.
Result<Eigen::Vector2d> project(const TsaiCamera& cam, const Eigen::Vector3d& pw_mm);
// Pixel -> viewing ray in the world frame (closed form).
Ray pixel_to_ray(const TsaiCamera& cam, const Eigen::Vector2d& uv_px);
// Pixel -> undistorted normalised image coordinates (Xu/f, Yu/f).
Eigen::Vector2d pixel_to_normalised(const TsaiCamera& cam, const Eigen::Vector2d& uv_px);

// Checks every field: positive sizes and lengths, finite values, R a proper
// rotation, and a distortion that stays monotonic across the image.
Status validate(const TsaiCamera& cam, const char* which = "camera");

// OpenCV-style pinhole with one radial term in normalised coordinates:
//   x_d = x_u*(1 + k1*r_u^2), u = fx*x_d + cx, v = fy*y_d + cy.
// The two radial models are inverses of each other only to first order, so
// k1 (or kappa1) is fitted by least squares over the image; the largest
// pixel disagreement of the fitted model over the image is returned.
struct PinholeK1 {
  int width = 0;
  int height = 0;
  double fx = 0, fy = 0, cx = 0, cy = 0, k1 = 0;
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d T = Eigen::Vector3d::Zero();
};

struct PinholeConversion {
  PinholeK1 pinhole;
  double max_error_px = 0;
};
struct TsaiConversion {
  TsaiCamera camera;
  double max_error_px = 0;
};

PinholeConversion to_pinhole(const TsaiCamera& cam);
// OpenCV knows no pixel pitch: pass the sensor's dy; dx is taken equal to dy
// and the aspect ratio goes into sx.
TsaiConversion from_pinhole(const PinholeK1& pin, double pixel_pitch_mm);

// Pixel position of a pinhole camera (for tests and conversions).
Eigen::Vector2d project_pinhole(const PinholeK1& pin, const Eigen::Vector3d& pw);

}  // namespace petra
