// Epipolar geometry of a calibrated Tsai stereo rig and the transfer of an
// operator's click from the left image to the right one (the paper's
// u2^T F u1 = 0, section 3.2).
//
// F works on *ideal* pixels: where a distortion-free camera with the same f,
// sx, dx, dy, cx, cy would see a point (u' = sx*Xu/dx + cx, v' = Yu/dy + cy).
// A real (distorted) pixel maps to its ideal pixel in closed form and back
// by the camera model's Newton inverse, so epipolar lines are straight in
// ideal pixels and curves in the images.
//
// Click transfer: the left pixel's viewing ray, from far (depth -> infinity)
// to near (min_depth_mm), projects onto a segment of the epipolar line; the
// right image is sampled along its curve (distortion applied) every step_px
// and each position scored by zero-mean normalised cross-correlation (ZNCC)
// of a (2h+1)^2 window with the window around the click; the best score is
// refined to sub-sample by a parabola and both rays are intersected.
//
// Memory: no heap, no I/O. transfer_click keeps the left window
// ((2*kMaxClickHalfWindow+1)^2 doubles, 7.7 KB) and up to kMaxClickSamples
// scores (16 KB) on the stack. Time: samples * (2h+1)^2 bilinear reads.
#pragma once

#include <Eigen/Core>

#include "algo/camera/camera_model.hpp"
#include "algo/core/image_view.hpp"
#include "algo/core/result.hpp"

namespace petra {

inline constexpr int kMaxClickHalfWindow = 15;
inline constexpr int kMaxClickSamples = 2048;

// Distorted pixel -> ideal pixel (closed form).
Eigen::Vector2d ideal_pixel(const TsaiCamera& cam, const Eigen::Vector2d& uv_px);
// Ideal pixel -> distorted pixel; fails where the model has no inverse.
Result<Eigen::Vector2d> distorted_pixel(const TsaiCamera& cam, const Eigen::Vector2d& ideal_px);
// K: normalised image coordinates (Xc/Zc, Yc/Zc, 1) -> homogeneous ideal pixels.
Eigen::Matrix3d ideal_intrinsics(const TsaiCamera& cam);

// F with [ideal_right; 1]^T F [ideal_left; 1] = 0, scaled to unit Frobenius
// norm. Fails (degenerate) when the cameras share their optical centre.
Result<Eigen::Matrix3d> fundamental_matrix(const StereoRig& rig);

// The right image's epipolar line of a left ideal pixel: (a, b, c) with
// a u + b v + c = 0 in ideal pixels and a^2 + b^2 = 1, so a point's signed
// distance to it is a u + b v + c.
Eigen::Vector3d epipolar_line(const Eigen::Matrix3d& f, const Eigen::Vector2d& left_ideal_px);

// Where the point at depth_mm (along the left camera's axis) on the ray of a
// left pixel appears in the right image (distorted pixels).
Result<Eigen::Vector2d> right_pixel_at_depth(const StereoRig& rig, const Eigen::Vector2d& left_px,
                                             double depth_mm);

// The point nearest to two rays (midpoint of their common perpendicular) and
// the distance between them; fails for parallel rays.
struct RayMeeting {
  Eigen::Vector3d point_mm;
  double gap_mm = 0;
};
Result<RayMeeting> meet_rays(const Ray& a, const Ray& b);

struct ClickOptions {
  int half_window = 7;        // ZNCC window 2h+1 px, 1..kMaxClickHalfWindow
  double min_depth_mm = 100;  // nearest point searched along the ray
  double max_depth_mm = 1e9;  // farthest (1e9: to infinity)
  double step_px = 0.5;       // along the curve; widened to keep within kMaxClickSamples
  double min_texture = 3.0;   // std dev of the click window, gray levels
};

struct ClickMatch {
  Eigen::Vector2d right_px;    // best match in the right image (distorted pixels)
  double score = 0;            // ZNCC of the best match, -1..1
  double runner_up = -1;       // best ZNCC at least a window away from it (ambiguity)
  Eigen::Vector3d point_mm;    // the 3D point in the world frame of the rig
  double ray_gap_mm = 0;       // distance between the two rays at the point
  double depth_mm = 0;         // along the left camera's axis
  int samples = 0;             // positions scored
  bool at_search_end = false;  // best at the first or last scored position: the true
                               // match may lie outside the searched depth range
};

// Fails with a reason: click outside the image or too near its border for
// the window, a window without texture, no part of the epipolar segment
// inside the right image, or the two images not matching the rig's sizes.
Result<ClickMatch> transfer_click(const StereoRig& rig, ConstGray8View left, ConstGray8View right,
                                  const Eigen::Vector2d& left_px, const ClickOptions& options);

}  // namespace petra
