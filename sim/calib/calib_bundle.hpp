// Joint refinement of Tsai cameras and board poses (ground tool): minimises
// the pixel reprojection error of every observed board corner over the free
// intrinsics of each camera (f, kappa1, principal point, sx), the pose of
// each camera relative to camera 0 (the rig) and the pose of the board in
// each view relative to camera 0. One camera and no rig is the single-camera
// case. Residuals go through the full camera model (algo/camera/camera_model),
// distortion inverted exactly; Jacobians are analytic (the distortion's by
// implicit differentiation); rotations are updated as R <- exp([d]x) R.
// Pixel pitch dx, dy is never estimated: only f/dx and f/dy are observable.
#pragma once

#include <Eigen/Core>
#include <array>
#include <vector>

#include "algo/camera/camera_model.hpp"
#include "algo/core/result.hpp"
#include "sim/calib/levenberg_marquardt.hpp"

namespace petra::calib {

// A rigid transform P' = R P + T (mm).
struct Pose {
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d T = Eigen::Vector3d::Zero();
};

struct IntrinsicsMask {  // true = estimated
  bool f = true;
  bool kappa1 = true;
  bool centre = true;
  bool sx = true;
};

struct BundleObservation {
  int camera = 0;
  int view = 0;
  Eigen::Vector3d board_mm;  // corner on the board (z = 0)
  Eigen::Vector2d uv_px;     // where it was detected
};

struct Bundle {
  std::vector<TsaiCamera> cameras;   // intrinsics; R and T are ignored
  std::vector<IntrinsicsMask> free;  // one per camera
  std::vector<Pose> rig;             // camera 0 -> camera k; rig[0] stays the identity
  std::vector<Pose> views;           // board of view v -> camera 0
  std::vector<BundleObservation> observations;
};

// Intrinsic parameter order in BundleFit::sigma.
enum IntrinsicIndex { kF = 0, kKappa1, kCx, kCy, kSx, kIntrinsicCount };

struct BundleFit {
  double rms_px = 0;                          // sqrt(mean |residual|^2) over observations
  std::vector<Eigen::Vector2d> residuals_px;  // predicted - observed, per observation
  // One-sigma uncertainty of each camera's intrinsics from the residual
  // scatter; 0 for fixed parameters, infinity where the data do not determine
  // the parameter (a singular normal matrix).
  std::vector<std::array<double, kIntrinsicCount>> sigma;
  int iterations = 0;
};

// Refines b in place. Fails when the start is outside the model's domain or
// there are fewer residuals than parameters.
Result<BundleFit> refine_bundle(Bundle& b, const LmOptions& options = {});

// Residuals (predicted - observed) of the current state; fails like project().
Result<std::vector<Eigen::Vector2d>> bundle_residuals(const Bundle& b);

}  // namespace petra::calib
