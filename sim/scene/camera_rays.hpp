// Viewing rays of one Tsai camera for the renderer: exactly algo's
// pixel_to_ray (same formulas, same Eigen expressions; a test checks they
// agree bit for bit over the image), with the per-camera constants hoisted
// out of the loop and compiled with the renderer, which casts ~10^7 rays
// per scene.
#pragma once

#include <Eigen/Core>

#include "algo/camera/camera_model.hpp"

namespace petra::sim {

class CameraRays {
 public:
  explicit CameraRays(const TsaiCamera& cam) : cam_(cam), origin_(camera_centre_world(cam)) {}

  const Eigen::Vector3d& origin() const { return origin_; }

  // Unit direction, in the world frame, of the ray through pixel (u, v).
  Eigen::Vector3d direction(double u, double v) const {
    const Eigen::Vector2d pd((u - cam_.cx_px) * cam_.dx_mm / cam_.sx,
                             (v - cam_.cy_px) * cam_.dy_mm);
    const Eigen::Vector2d n = undistort(pd) / cam_.f_mm;
    const Eigen::Vector3d dir_cam(n.x(), n.y(), 1.0);
    return (cam_.R.transpose() * dir_cam).normalized();
  }

 private:
  Eigen::Vector2d undistort(const Eigen::Vector2d& pd) const {
    return pd * (1.0 + cam_.kappa1 * pd.squaredNorm());
  }

  TsaiCamera cam_;
  Eigen::Vector3d origin_;
};

}  // namespace petra::sim
