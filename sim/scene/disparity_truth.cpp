#include "sim/scene/disparity_truth.hpp"

#include <cmath>
#include <limits>

#include "sim/scene/ray_cast.hpp"

namespace petra::sim {

namespace {

bool inside_original(const TsaiCamera& cam, const Eigen::Vector2d& uv) {
  return uv.x() >= -0.5 && uv.x() <= cam.width - 0.5 && uv.y() >= -0.5 &&
         uv.y() <= cam.height - 0.5;
}

}  // namespace

bool visible_from(const Scene& scene, const Eigen::Vector3d& centre, const Eigen::Vector3d& p) {
  const Eigen::Vector3d to = p - centre;
  const double dist = to.norm();
  const SceneHit hit = trace(scene, centre, to / dist);
  // Reaching p (to rounding, or to the marching tolerance of relief and rough
  // faces) means nothing lies in front of it.
  const double tol = clean_geometry(scene) ? 1e-6 : 0.02;
  return hit.surface != kSky && hit.t >= dist * (1.0 - 1e-9) - tol;
}

Result<RectifiedTruth> render_rectified_truth(const Scene& scene) {
  if (!clean_geometry(scene) || scene.tilted || scene.calib_residual_px > 0)
    return render_rectified_truth_real(scene);
  const int w = kImageWidth, h = kImageHeight;
  auto pair = rectify_geometry(scene.rig, w, h);
  if (!pair) return pair.error();
  RectifiedTruth out;
  out.pair = *pair;
  out.disparity = io::FloatImage(w, h, std::numeric_limits<float>::infinity());
  out.shadow_mask = io::GrayImage(w, h);
  const RectifiedCamera& rl = pair->left;
  const Eigen::Vector3d cl = camera_centre_world(scene.rig.left);
  const Eigen::Vector3d cr = camera_centre_world(scene.rig.right);
  const Eigen::Matrix3d to_world = rl.R.transpose();
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      auto orig = rectified_to_original(scene.rig.left, rl, {double(i), double(j)});
      if (!orig || !inside_original(scene.rig.left, *orig)) continue;
      const Eigen::Vector3d dir =
          (to_world * Eigen::Vector3d((i - rl.cx_px) / rl.f_px, (j - rl.cy_px) / rl.f_px, 1.0))
              .normalized();
      const SceneHit hit = trace(scene, cl, dir);
      if (hit.surface == kSky) continue;
      const std::size_t k = static_cast<std::size_t>(j) * w + i;
      out.shadow_mask.pixels[k] = in_shadow(scene, hit) ? 255 : 0;
      if (!visible_from(scene, cr, hit.point)) continue;
      auto uv_right = project(scene.rig.right, hit.point);
      if (!uv_right || !inside_original(scene.rig.right, *uv_right)) continue;
      auto rp = rectified_project(*pair, hit.point);
      if (!rp) continue;
      const double u_right = rp->uv_left.x() - rp->disparity;
      if (u_right < -0.5 || u_right > w - 0.5) continue;
      out.disparity.data[k] = static_cast<float>(rp->disparity);
    }
  return out;
}

}  // namespace petra::sim
