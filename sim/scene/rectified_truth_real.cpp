// Disparity and shadow truth of the realistic world (disparity_truth.hpp):
// the images come from the true cameras, but the matchers rectify them with
// calib.json's rig. A rectified left pixel is mapped to the original left
// pixel by calib.json's left camera, that pixel's TRUE ray is cast, and the
// point it hits is projected by the TRUE right camera and mapped to the
// rectified right view by calib.json's right camera: d = u_left - u_right,
// and v_right - v_left is the vertical disparity a calibration residual leaves.
#include <cmath>
#include <limits>

#include "sim/scene/camera_rays.hpp"
#include "sim/scene/disparity_truth.hpp"
#include "sim/scene/ray_cast.hpp"

namespace petra::sim {

namespace {

bool inside(const TsaiCamera& cam, const Eigen::Vector2d& uv) {
  return uv.x() >= -0.5 && uv.x() <= cam.width - 0.5 && uv.y() >= -0.5 &&
         uv.y() <= cam.height - 0.5;
}

}  // namespace

Result<RectifiedTruth> render_rectified_truth_real(const Scene& scene) {
  const int w = kImageWidth, h = kImageHeight;
  auto pair = rectify_geometry(scene.calib_rig, w, h);
  if (!pair) return pair.error();
  constexpr float kNone = std::numeric_limits<float>::quiet_NaN();
  RectifiedTruth out;
  out.pair = *pair;
  out.disparity = io::FloatImage(w, h, std::numeric_limits<float>::infinity());
  out.shadow_mask = io::GrayImage(w, h);
  out.vertical = io::FloatImage(w, h, kNone);
  out.surface_height = io::FloatImage(w, h, kNone);
  out.face_points.resize(scene.rock.faces.size());
  const CameraRays left(scene.rig.left);
  const Eigen::Vector3d cr = camera_centre_world(scene.rig.right);
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      auto orig = rectified_to_original(scene.calib_rig.left, pair->left, {double(i), double(j)});
      if (!orig || !inside(scene.rig.left, *orig)) continue;
      const SceneHit hit = trace(scene, left.origin(), left.direction(orig->x(), orig->y()));
      if (hit.surface == kSky) continue;
      const std::size_t k = static_cast<std::size_t>(j) * w + i;
      out.shadow_mask.pixels[k] = in_shadow(scene, hit) ? 255 : 0;
      if (hit.surface == kGround) out.surface_height.data[k] = static_cast<float>(hit.point.z());
      if (hit.surface >= kRockFace0 && hit.surface < kStone0)
        out.face_points[static_cast<std::size_t>(hit.surface - kRockFace0)].push_back(hit.point);
      if (!visible_from(scene, cr, hit.point)) continue;
      auto uv_right = project(scene.rig.right, hit.point);
      if (!uv_right || !inside(scene.rig.right, *uv_right)) continue;
      auto rr = original_to_rectified(scene.calib_rig.right, pair->right, *uv_right);
      if (!rr || rr->x() < -0.5 || rr->x() > w - 0.5) continue;
      out.disparity.data[k] = static_cast<float>(i - rr->x());
      out.vertical.data[k] = static_cast<float>(rr->y() - j);
    }
  return out;
}

}  // namespace petra::sim
