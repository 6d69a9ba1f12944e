// Epipolar rectification geometry (docs/method.md 3b): both cameras are rotated to a
// common orientation whose x axis is the baseline, with one distortion-free
// virtual camera model (same f, cx, cy) for both, so a world point appears on
// the same row in both rectified images and
//   d = u_left - u_right = f_px * B / Z_rect   (d > 0 in front of the rig),
// matching the Middlebury convention "d maps left x to right x - d".
// Pure geometry; the remap tables are built on it by algo/camera/rectify.
#pragma once

#include <Eigen/Core>

#include "algo/camera/camera_model.hpp"
#include "algo/core/result.hpp"

namespace petra {

// A distortion-free pinhole with square pixels in the rectified frame.
struct RectifiedCamera {
  int width = 0;
  int height = 0;
  double f_px = 0;
  double cx_px = 0;
  double cy_px = 0;
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();  // world -> rectified camera
  Eigen::Vector3d T_mm = Eigen::Vector3d::Zero();   // world -> rectified camera
};

struct RectifiedPair {
  RectifiedCamera left;
  RectifiedCamera right;
  double baseline_mm = 0;
};

// Rectifying rotations and the common virtual camera for an output of
// width x height pixels (usually the input size). The focal length is the
// mean of the two cameras' vertical focal lengths in pixels; the principal
// point centres the mean of the two original image centres. Fails for a
// degenerate rig (coincident centres, baseline along the optical axis).
Result<RectifiedPair> rectify_geometry(const StereoRig& rig, int width, int height);

// Rectified pixel -> original (distorted) pixel of the same camera.
Result<Eigen::Vector2d> rectified_to_original(const TsaiCamera& cam, const RectifiedCamera& rect,
                                              const Eigen::Vector2d& uv_rect);
// Original (distorted) pixel -> rectified pixel of the same camera. Fails when
// the ray leaves the rectified camera's front half-space.
Result<Eigen::Vector2d> original_to_rectified(const TsaiCamera& cam, const RectifiedCamera& rect,
                                              const Eigen::Vector2d& uv);

// World point of a rectified correspondence (u_left, v) <-> (u_left - d, v).
// Fails for d <= 0 (at or beyond infinity).
Result<Eigen::Vector3d> rectified_point(const RectifiedPair& pair, double u_left, double v,
                                        double disparity);
// Disparity of a world point in the rectified pair (left view), and its
// rectified left pixel. Fails for points behind the rig.
struct RectifiedProjection {
  Eigen::Vector2d uv_left;
  double disparity = 0;
};
Result<RectifiedProjection> rectified_project(const RectifiedPair& pair, const Eigen::Vector3d& pw);

}  // namespace petra
