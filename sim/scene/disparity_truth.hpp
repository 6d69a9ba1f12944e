// Ground-truth disparity in the rectified geometry the matchers use:
// rectify_geometry(rig, 1024, 768), left view, d = u_left - u_right (px).
// For each rectified left pixel centre the ray of the rectified left camera
// is cast into the scene; the pixel gets the exact disparity of the point it
// hits (rectified_project), or +inf when there is no valid correspondence:
//   - the pixel maps outside the original left image (no data there),
//   - the ray meets nothing (sky),
//   - the point is hidden from the right camera (occluded),
//   - the point falls outside the original right image, or its rectified
//     right position u_left - d lies outside the rectified image.
// Also the shadow truth for the same rectified left pixels (point-sampled).
// In the realistic world (sloped frame, relief, rough faces, stones, a
// calibration residual) the rectification is calib.json's and the rays are
// the true cameras' (rectified_truth_real.cpp).
#pragma once

#include <vector>

#include "algo/camera/rectify_geometry.hpp"
#include "sim/io/image_io.hpp"
#include "sim/scene/scene.hpp"

namespace petra::sim {

struct RectifiedTruth {
  RectifiedPair pair;
  io::FloatImage disparity;   // +inf where invalid
  io::GrayImage shadow_mask;  // 255 in shadow (cast or self), else 0; 0 where no data
  // Realistic world only (empty otherwise).
  io::FloatImage vertical;        // v_right - v_left of each valid pixel (px), NaN elsewhere
  io::FloatImage surface_height;  // ground hits: height above the local base plane, NaN elsewhere
  std::vector<std::vector<Eigen::Vector3d>> face_points;  // local-frame hits per rock face
};

Result<RectifiedTruth> render_rectified_truth(const Scene& scene);
Result<RectifiedTruth> render_rectified_truth_real(const Scene& scene);

// True when world point p (on a scene surface) is the first thing the camera
// at `centre` sees along its line of sight.
bool visible_from(const Scene& scene, const Eigen::Vector3d& centre, const Eigen::Vector3d& p);

}  // namespace petra::sim
