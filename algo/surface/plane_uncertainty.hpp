// Uncertainty of a fitted plane from the stereo depth-noise model
// (docs/method.md 2a; sigma_Z ~ Z^2 sigma_d / (f B)).
// Each sample is a point measured along its viewing ray with the range error
// sigma_R = R^2 sigma_d / (f B) (R: range to the left camera, f: focal length
// in pixels, B: baseline in mm, sigma_d: the noise of the disparities as
// reconstructed, in pixels). Its error across the plane is sigma_R |n . ray|.
// A sample may stand for several pixels (a triangle covers area / pixel
// footprint of them). Neighbouring disparities share their errors (the
// matcher's window and the mean filter average over a box of correlation_px
// x correlation_px pixels), so N pixels hold N / correlation_px^2
// independent measurements, each with sigma_d. Counted as independent, the
// clean scene set's planes erred by a median 2.5 and up to 60 of their
// sigmas (docs/log.md, 2026-12-03).
// Linearised least squares about the plane (n, through `centre`), in the
// frame (e1, e2, n): offset along n = a u + b v + c, Jacobian [u, v, 1].
// Covariance = (sum w J^T J)^-1, scaled by the reduced chi-square of the
// samples' residuals when it exceeds 1 (roughness or curvature the noise
// model does not explain widens the plane's uncertainty, never narrows it).
// Outputs: normal 1-sigma = sqrt(var a + var b) in degrees (the RMS angle
// between the fitted and the true normal), offset 1-sigma along n at
// `centre` in mm. No heap; O(1) memory, one pass over the samples.
#pragma once

#include <Eigen/Core>

#include "algo/core/result.hpp"

namespace petra {

// The matcher's disparity noise (sigma_d) after the mean filter, px: the one
// default of the depth-noise model, for the ground tolerance and the planes.
inline constexpr double kDisparitySigmaPx = 0.3;

// The rig's depth noise. A zero focal length or baseline: unknown rig (the
// fit's residuals alone set the uncertainty).
struct DepthNoise {
  double focal_px = 0;
  double baseline_mm = 0;
  double sigma_disparity_px = 0;
  double correlation_px = 1;  // side of the box over which disparity errors are shared
  bool known() const { return focal_px > 0 && baseline_mm > 0 && sigma_disparity_px > 0; }
  // Range error at range r (mm), along the viewing ray.
  double sigma_range_mm(double r_mm) const {
    return known() ? r_mm * r_mm * sigma_disparity_px / (focal_px * baseline_mm) : 0.0;
  }
};

struct PlaneUncertainty {
  double normal_sigma_deg = 0;  // RMS angle of the normal about the truth
  double offset_sigma_mm = 0;   // along the normal, at the centre
  double noise_mm = 0;          // model's RMS error across the plane, per pixel
  double chi2_scale = 1;        // reduced chi-square applied (>= 1)
  double pixels = 0;            // pixels counted (independent: pixels / correlation_px^2)
};

// Accumulates samples about a given plane; finish() inverts the information.
class PlaneInformation {
 public:
  PlaneInformation(const Eigen::Vector3d& normal, const Eigen::Vector3d& centre,
                   const Eigen::Vector3d& camera_mm, const DepthNoise& noise);
  // A point measured `pixels` times independently (pixels > 0).
  void add(const Eigen::Vector3d& p, double pixels);
  // Fails when fewer than 4 pixels were added or the samples do not span
  // two directions in the plane.
  Result<PlaneUncertainty> finish() const;

 private:
  Eigen::Vector3d n_, c_, cam_, e1_, e2_;
  DepthNoise noise_;
  Eigen::Matrix3d info_ = Eigen::Matrix3d::Zero();  // sum w J^T J
  Eigen::Vector3d jr_ = Eigen::Vector3d::Zero();    // sum w J r
  double chi2_ = 0, pixels_ = 0, noise_ss_ = 0;
  double fallback_ss_ = 0;  // sum pixels r^2, unknown rig
};

Status validate(const DepthNoise& noise);

}  // namespace petra
