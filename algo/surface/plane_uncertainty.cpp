#include "algo/surface/plane_uncertainty.hpp"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>

namespace petra {

namespace {

// A ray grazing the plane moves its point within the plane; the pixel's own
// position error then dominates, which this floor stands for.
constexpr double kMinRayCos = 0.1;

}  // namespace

Status validate(const DepthNoise& noise) {
  if (!(noise.focal_px >= 0) || !(noise.baseline_mm >= 0) || !std::isfinite(noise.focal_px) ||
      !std::isfinite(noise.baseline_mm))
    return Error::make(Errc::invalid_argument,
                       "depth noise: focal_px and baseline_mm must be >= 0");
  if (!(noise.correlation_px >= 1.0 && noise.correlation_px <= 64.0))
    return Error::make(Errc::invalid_argument, "depth noise: correlation_px %.3g not in [1, 64]",
                       noise.correlation_px);
  if (!(noise.sigma_disparity_px > 0.0 && noise.sigma_disparity_px <= 10.0))
    return Error::make(Errc::invalid_argument,
                       "depth noise: sigma_disparity_px %.3g not in (0, 10]",
                       noise.sigma_disparity_px);
  return {};
}

PlaneInformation::PlaneInformation(const Eigen::Vector3d& normal, const Eigen::Vector3d& centre,
                                   const Eigen::Vector3d& camera_mm, const DepthNoise& noise)
    : n_(normal.normalized()), c_(centre), cam_(camera_mm), noise_(noise) {
  const Eigen::Vector3d helper =
      std::abs(n_.z()) < 0.9 ? Eigen::Vector3d::UnitZ() : Eigen::Vector3d::UnitX();
  e1_ = helper.cross(n_).normalized();
  e2_ = n_.cross(e1_);
}

void PlaneInformation::add(const Eigen::Vector3d& p, double pixels) {
  if (!(pixels > 0)) return;
  const Eigen::Vector3d q = p - c_;
  const Eigen::Vector3d to = p - cam_;
  const double range = to.norm();
  double var = 1.0;  // unknown rig: unit weights, the residuals set the scale
  if (noise_.known() && range > 0) {
    const double across =
        noise_.sigma_range_mm(range) * std::max(std::abs(n_.dot(to) / range), kMinRayCos);
    var = across * across;
    noise_ss_ += pixels * var;
  }
  const double w = pixels / (noise_.correlation_px * noise_.correlation_px) / var;
  const Eigen::Vector3d j(q.dot(e1_), q.dot(e2_), 1.0);
  const double r = q.dot(n_);
  info_.noalias() += w * j * j.transpose();
  jr_ += w * r * j;
  chi2_ += w * r * r;
  pixels_ += pixels;
}

Result<PlaneUncertainty> PlaneInformation::finish() const {
  if (!(pixels_ >= 4))
    return Error::make(Errc::degenerate, "plane uncertainty: %.1f pixels, need at least 4",
                       pixels_);
  Eigen::FullPivLU<Eigen::Matrix3d> lu(info_);
  const double scale = info_.diagonal().maxCoeff();
  lu.setThreshold(1e-9);
  if (!(scale > 0) || lu.rank() < 3)
    return Error::make(Errc::degenerate, "plane uncertainty: the samples span one direction");
  Eigen::Matrix3d cov = lu.inverse();
  // Residual of the best plane under these weights (the given plane may
  // differ slightly from it).
  const double chi2_min = std::max(0.0, chi2_ - jr_.dot(cov * jr_));
  const double independent = pixels_ / (noise_.correlation_px * noise_.correlation_px);
  const double dof = std::max(1.0, independent - 3.0);
  PlaneUncertainty out;
  out.pixels = pixels_;
  out.chi2_scale = noise_.known() ? std::max(1.0, chi2_min / dof) : chi2_min / dof;
  cov *= out.chi2_scale;
  out.normal_sigma_deg = std::sqrt(std::max(0.0, cov(0, 0) + cov(1, 1))) * 180.0 / M_PI;
  out.offset_sigma_mm = std::sqrt(std::max(0.0, cov(2, 2)));
  out.noise_mm = noise_.known() ? std::sqrt(noise_ss_ / pixels_) : 0.0;
  return out;
}

}  // namespace petra
