// One camera from several views of a planar target (ground tool):
//   1. duplicate views (same corners within duplicate_px) are set aside;
//   2. Tsai's two-step on each view with the principal point at the image
//      centre and sx = 1 (what one plane cannot give) -> f, kappa1, pose;
//      views nearly parallel to the image give no f;
//   3. f and kappa1 start at the medians over the tilted views; every view's
//      pose is re-solved with that f;
//   4. joint Levenberg-Marquardt over f, kappa1, principal point, sx and all
//      poses (calib_bundle). Several tilted views determine the principal
//      point and sx (as in Zhang's method); when the fitted uncertainty says
//      they are not determined, they are fixed at the image centre and 1 and
//      a note says so.
// Never observable from planar views: the pixel pitch (only f/dx, f/dy and
// kappa1*dy^2 are), so dx, dy come with the sensor and scale f and kappa1.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "algo/camera/camera_model.hpp"
#include "algo/core/result.hpp"
#include "sim/calib/calib_bundle.hpp"
#include "sim/calib/tsai_view.hpp"

namespace petra::calib {

struct CameraCalibOptions {
  bool estimate_sx = true;
  bool estimate_centre = true;
  double duplicate_px = 0.5;        // mean corner distance below which two views are one
  double max_centre_sigma_px = 10;  // principal point fixed when less certain than this
  double max_sx_sigma = 0.005;      // sx fixed at 1 when less certain than this
  int min_views = 3;
};

struct CameraCalibration {
  TsaiCamera camera;                            // intrinsics; R = I, T = 0
  IntrinsicsMask estimated;                     // which intrinsics were fitted
  std::vector<int> views;                       // indices of the input views used
  std::vector<Pose> poses;                      // board -> camera, one per used view
  std::vector<double> view_rms_px;              // one per used view
  double rms_px = 0;                            // over all corners of the used views
  std::array<double, kIntrinsicCount> sigma{};  // one-sigma uncertainties (bundle order)
  std::vector<std::string> notes;               // what was set aside or fixed, and why
};

// sensor: width, height, dx, dy (and sx when it is not estimated).
Result<CameraCalibration> calibrate_camera(const std::vector<PlanarView>& views,
                                           const TsaiCamera& sensor,
                                           const CameraCalibOptions& options = {});

}  // namespace petra::calib
