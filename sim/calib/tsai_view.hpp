// Tsai's two-step calibration of one camera from one view of a planar target
// (Tsai 1987, coplanar case; the paper's section 3.1). The sensor geometry
// (image size, pixel pitch dx, dy, scale factor sx, principal point) must be
// given: a single plane cannot separate them from the pose.
//   1. Radial alignment: distortion and f only stretch an image point along
//      the ray from the principal point, so Xd / Yd = Xc / Yc, which is linear
//      in (r1, r2, tx, r4, r5, ty). Solved as a homogeneous least-squares
//      problem (no division by ty, so any target origin works); the scale
//      comes from the 2x2 block being part of a rotation (largest singular
//      value 1), the sign from Xc, Yc sharing the signs of Xd, Yd, the third
//      row and column from orthonormality.
//   2. f and tz from the same equations with kappa1 = 0 (linear); a negative
//      f selects the other root of the rotation. Fails for a view nearly
//      parallel to the image plane (f and tz then only appear as f/tz) unless
//      f is given, in which case only tz is solved.
//   3. Levenberg-Marquardt on f, tz, kappa1 (pixel reprojection error).
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "algo/camera/camera_model.hpp"
#include "algo/core/result.hpp"

namespace petra::calib {

struct PlanarView {
  std::vector<Eigen::Vector2d> board_mm;  // target points (x, y) on the plane z = 0
  std::vector<Eigen::Vector2d> uv_px;     // their images
  std::string name;                       // for messages (e.g. the image file)
};

struct TsaiViewResult {
  TsaiCamera camera;    // sensor geometry as given; f, kappa1, R, T estimated
  double rms_px = 0;    // reprojection error after step 3
  double tilt_deg = 0;  // angle between the target's normal and the optical axis
};

// Views tilted less than this give no focal length (step 2 fails) unless f is known.
inline constexpr double kMinTiltDeg = 3.0;

Result<TsaiViewResult> tsai_calibrate_view(const PlanarView& view, const TsaiCamera& sensor,
                                           std::optional<double> known_f_mm = std::nullopt);

}  // namespace petra::calib
