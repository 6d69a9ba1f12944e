#include "algo/camera/camera_model.hpp"

#include <Eigen/Geometry>
#include <cmath>

namespace petra {

Result<Eigen::Vector2d> distort_sensor(double kappa1, const Eigen::Vector2d& pu) {
  const double ru = pu.norm();
  if (ru == 0.0 || kappa1 == 0.0) return Eigen::Vector2d(pu);
  if (kappa1 < 0.0) {
    // r + k r^3 peaks at r* = sqrt(-1/(3k)) with value 2/3 r*; beyond it, no solution.
    const double r_fold = std::sqrt(-1.0 / (3.0 * kappa1));
    if (ru > (2.0 / 3.0) * r_fold)
      return Error::make(Errc::no_solution, "distortion: radius %.6g mm beyond the model's fold",
                         ru);
  }
  // Newton on g(r) = r + k r^3 - ru. g is concave (k<0) or convex (k>0) and we
  // start at r = ru on the side from which Newton converges monotonically.
  double r = ru;
  for (int it = 0; it < 50; ++it) {
    const double g = r + kappa1 * r * r * r - ru;
    const double dg = 1.0 + 3.0 * kappa1 * r * r;
    const double step = g / dg;
    r -= step;
    if (std::abs(step) <= 1e-15 * ru) break;
  }
  return Eigen::Vector2d(pu * (r / ru));
}

Eigen::Vector2d undistort_sensor(double kappa1, const Eigen::Vector2d& pd) {
  return pd * (1.0 + kappa1 * pd.squaredNorm());
}

Eigen::Vector3d world_to_camera(const TsaiCamera& cam, const Eigen::Vector3d& pw) {
  return cam.R * pw + cam.T_mm;
}

Eigen::Vector3d camera_to_world(const TsaiCamera& cam, const Eigen::Vector3d& pc) {
  return cam.R.transpose() * (pc - cam.T_mm);
}

Eigen::Vector3d camera_centre_world(const TsaiCamera& cam) {
  return -(cam.R.transpose() * cam.T_mm);
}

Eigen::Vector2d pixel_to_sensor(const TsaiCamera& cam, const Eigen::Vector2d& uv) {
  return {(uv.x() - cam.cx_px) * cam.dx_mm / cam.sx, (uv.y() - cam.cy_px) * cam.dy_mm};
}

Eigen::Vector2d sensor_to_pixel(const TsaiCamera& cam, const Eigen::Vector2d& pd) {
  return {cam.sx * pd.x() / cam.dx_mm + cam.cx_px, pd.y() / cam.dy_mm + cam.cy_px};
}

Result<Eigen::Vector2d> project(const TsaiCamera& cam, const Eigen::Vector3d& pw) {
  const Eigen::Vector3d pc = world_to_camera(cam, pw);
  if (!(pc.z() > 0.0))
    return Error::make(Errc::out_of_range, "project: point not in front of the camera (Zc=%.6g mm)",
                       pc.z());
  const Eigen::Vector2d pu(cam.f_mm * pc.x() / pc.z(), cam.f_mm * pc.y() / pc.z());
  auto pd = distort_sensor(cam.kappa1, pu);
  if (!pd) return pd.error();
  return sensor_to_pixel(cam, *pd);
}

Eigen::Vector2d pixel_to_normalised(const TsaiCamera& cam, const Eigen::Vector2d& uv) {
  return undistort_sensor(cam.kappa1, pixel_to_sensor(cam, uv)) / cam.f_mm;
}

Ray pixel_to_ray(const TsaiCamera& cam, const Eigen::Vector2d& uv) {
  const Eigen::Vector2d n = pixel_to_normalised(cam, uv);
  const Eigen::Vector3d dir_cam(n.x(), n.y(), 1.0);
  return {camera_centre_world(cam), (cam.R.transpose() * dir_cam).normalized()};
}

namespace {

bool finite_all(const TsaiCamera& c) {
  return std::isfinite(c.f_mm) && std::isfinite(c.kappa1) && std::isfinite(c.sx) &&
         std::isfinite(c.cx_px) && std::isfinite(c.cy_px) && std::isfinite(c.dx_mm) &&
         std::isfinite(c.dy_mm) && c.R.allFinite() && c.T_mm.allFinite();
}

// Largest distorted sensor radius over the image corners.
double max_sensor_radius(const TsaiCamera& c) {
  double r = 0.0;
  const double us[2] = {-0.5, c.width - 0.5};
  const double vs[2] = {-0.5, c.height - 0.5};
  for (double u : us)
    for (double v : vs) r = std::max(r, pixel_to_sensor(c, {u, v}).norm());
  return r;
}

}  // namespace

Status validate(const TsaiCamera& c, const char* which) {
  if (c.width <= 0) return Error::make(Errc::non_positive, "%s.width must be > 0", which);
  if (c.height <= 0) return Error::make(Errc::non_positive, "%s.height must be > 0", which);
  if (!finite_all(c))
    return Error::make(Errc::invalid_argument, "%s: a value is not finite", which);
  if (c.f_mm <= 0)
    return Error::make(Errc::non_positive, "%s.f must be > 0 (got %g)", which, c.f_mm);
  if (c.dx_mm <= 0)
    return Error::make(Errc::non_positive, "%s.dx must be > 0 (got %g)", which, c.dx_mm);
  if (c.dy_mm <= 0)
    return Error::make(Errc::non_positive, "%s.dy must be > 0 (got %g)", which, c.dy_mm);
  if (c.sx <= 0) return Error::make(Errc::non_positive, "%s.sx must be > 0 (got %g)", which, c.sx);
  const double ortho = (c.R * c.R.transpose() - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  if (ortho > 1e-6)
    return Error::make(Errc::not_orthonormal, "%s.R is not orthonormal (|R R^T - I| = %.3g)", which,
                       ortho);
  if (c.R.determinant() < 0)
    return Error::make(Errc::not_orthonormal, "%s.R is a reflection (det = -1)", which);
  const double rmax = max_sensor_radius(c);
  if (1.0 + 3.0 * c.kappa1 * rmax * rmax <= 0.0)
    return Error::make(Errc::invalid_argument,
                       "%s.kappa1 = %g folds the image (distortion not monotonic within %.4g mm)",
                       which, c.kappa1, rmax);
  return {};
}

Eigen::Vector2d project_pinhole(const PinholeK1& p, const Eigen::Vector3d& pw) {
  const Eigen::Vector3d pc = p.R * pw + p.T;
  const double x = pc.x() / pc.z(), y = pc.y() / pc.z();
  const double s = 1.0 + p.k1 * (x * x + y * y);
  return {p.fx * x * s + p.cx, p.fy * y * s + p.cy};
}

namespace {
constexpr int kFitGrid = 24;  // samples per image axis for the k1/kappa1 fits
}

PinholeConversion to_pinhole(const TsaiCamera& c) {
  PinholeConversion out;
  PinholeK1& p = out.pinhole;
  p.width = c.width;
  p.height = c.height;
  p.fx = c.f_mm * c.sx / c.dx_mm;
  p.fy = c.f_mm / c.dy_mm;
  p.cx = c.cx_px;
  p.cy = c.cy_px;
  p.R = c.R;
  p.T = c.T_mm;
  // Fit k1: x_d - x_u = k1 * x_u * r_u^2 over a pixel grid (normalised units).
  double num = 0, den = 0;
  for (int j = 0; j <= kFitGrid; ++j)
    for (int i = 0; i <= kFitGrid; ++i) {
      const Eigen::Vector2d uv(i * (c.width - 1.0) / kFitGrid, j * (c.height - 1.0) / kFitGrid);
      const Eigen::Vector2d xd = pixel_to_sensor(c, uv) / c.f_mm;
      const Eigen::Vector2d xu = pixel_to_normalised(c, uv);
      const Eigen::Vector2d a = xu * xu.squaredNorm();
      num += a.dot(xd - xu);
      den += a.squaredNorm();
    }
  p.k1 = den > 0 ? num / den : 0.0;
  for (int j = 0; j <= kFitGrid; ++j)
    for (int i = 0; i <= kFitGrid; ++i) {
      const Eigen::Vector2d uv(i * (c.width - 1.0) / kFitGrid, j * (c.height - 1.0) / kFitGrid);
      const Eigen::Vector2d xu = pixel_to_normalised(c, uv);
      const double s = 1.0 + p.k1 * xu.squaredNorm();
      const Eigen::Vector2d back(p.fx * xu.x() * s + p.cx, p.fy * xu.y() * s + p.cy);
      out.max_error_px = std::max(out.max_error_px, (back - uv).norm());
    }
  return out;
}

TsaiConversion from_pinhole(const PinholeK1& p, double pitch_mm) {
  TsaiConversion out;
  TsaiCamera& c = out.camera;
  c.width = p.width;
  c.height = p.height;
  c.dx_mm = pitch_mm;
  c.dy_mm = pitch_mm;
  c.f_mm = p.fy * pitch_mm;
  c.sx = p.fx / p.fy;
  c.cx_px = p.cx;
  c.cy_px = p.cy;
  c.R = p.R;
  c.T_mm = p.T;
  // Sample pixels, undistort them through the pinhole model by fixed-point
  // iteration, then fit Xu - Xd = kappa1 * Xd * r_d^2 (mm).
  auto undistort_cv = [&](const Eigen::Vector2d& uv) {
    const Eigen::Vector2d xd((uv.x() - p.cx) / p.fx, (uv.y() - p.cy) / p.fy);
    Eigen::Vector2d xu = xd;
    for (int it = 0; it < 100; ++it) xu = xd / (1.0 + p.k1 * xu.squaredNorm());
    return xu;
  };
  double num = 0, den = 0;
  for (int j = 0; j <= kFitGrid; ++j)
    for (int i = 0; i <= kFitGrid; ++i) {
      const Eigen::Vector2d uv(i * (p.width - 1.0) / kFitGrid, j * (p.height - 1.0) / kFitGrid);
      const Eigen::Vector2d pd = pixel_to_sensor(c, uv);
      const Eigen::Vector2d pu = undistort_cv(uv) * c.f_mm;
      const Eigen::Vector2d a = pd * pd.squaredNorm();
      num += a.dot(pu - pd);
      den += a.squaredNorm();
    }
  c.kappa1 = den > 0 ? num / den : 0.0;
  for (int j = 0; j <= kFitGrid; ++j)
    for (int i = 0; i <= kFitGrid; ++i) {
      const Eigen::Vector2d uv(i * (p.width - 1.0) / kFitGrid, j * (p.height - 1.0) / kFitGrid);
      const Eigen::Vector2d xu = pixel_to_normalised(c, uv);
      const double s = 1.0 + p.k1 * xu.squaredNorm();
      const Eigen::Vector2d back(p.fx * xu.x() * s + p.cx, p.fy * xu.y() * s + p.cy);
      out.max_error_px = std::max(out.max_error_px, (back - uv).norm());
    }
  return out;
}

}  // namespace petra
