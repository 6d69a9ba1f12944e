#include "sim/calib/tsai_view.hpp"

#include <Eigen/Dense>
#include <cmath>

#include "sim/calib/levenberg_marquardt.hpp"

namespace petra::calib {

namespace {

constexpr double kRadToDeg = 180.0 / 3.14159265358979323846;

Eigen::Matrix3d nearest_rotation(const Eigen::Matrix3d& m) {
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(m, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d r = svd.matrixU() * svd.matrixV().transpose();
  if (r.determinant() < 0) {
    Eigen::Matrix3d u = svd.matrixU();
    u.col(2) *= -1;
    r = u * svd.matrixV().transpose();
  }
  return r;
}

double reprojection_rms(const TsaiCamera& cam, const PlanarView& view, bool& ok) {
  double ss = 0;
  ok = true;
  for (std::size_t k = 0; k < view.uv_px.size(); ++k) {
    auto uv = project(cam, Eigen::Vector3d(view.board_mm[k].x(), view.board_mm[k].y(), 0));
    if (!uv) {
      ok = false;
      return 0;
    }
    ss += (*uv - view.uv_px[k]).squaredNorm();
  }
  return std::sqrt(ss / static_cast<double>(view.uv_px.size()));
}

// Step 2: f and tz (or tz alone) from f*y - Yd*tz = Yd*w and f*x - Xd*tz = Xd*w.
struct FocalDepth {
  double f, tz;
};

std::optional<FocalDepth> solve_f_tz(const Eigen::Matrix3d& r, double tx, double ty,
                                     const std::vector<Eigen::Vector2d>& pd, const PlanarView& view,
                                     std::optional<double> known_f, double& residual) {
  const std::size_t n = pd.size();
  Eigen::MatrixXd a(2 * n, 2);
  Eigen::VectorXd b(2 * n);
  for (std::size_t k = 0; k < n; ++k) {
    const double xw = view.board_mm[k].x(), yw = view.board_mm[k].y();
    const double x = r(0, 0) * xw + r(0, 1) * yw + tx;
    const double y = r(1, 0) * xw + r(1, 1) * yw + ty;
    const double w = r(2, 0) * xw + r(2, 1) * yw;
    a.row(static_cast<Eigen::Index>(2 * k)) << x, -pd[k].x();
    b(static_cast<Eigen::Index>(2 * k)) = pd[k].x() * w;
    a.row(static_cast<Eigen::Index>(2 * k + 1)) << y, -pd[k].y();
    b(static_cast<Eigen::Index>(2 * k + 1)) = pd[k].y() * w;
  }
  if (known_f) {
    // -Pd*tz = Pd*w - f*x  ->  tz by least squares.
    const Eigen::VectorXd rhs = b - *known_f * a.col(0);
    const double den = a.col(1).squaredNorm();
    if (!(den > 0)) return std::nullopt;
    const double tz = a.col(1).dot(rhs) / den;
    residual = (rhs - tz * a.col(1)).norm();
    return FocalDepth{*known_f, tz};
  }
  const Eigen::Vector2d s = a.colPivHouseholderQr().solve(b);
  if (!s.allFinite()) return std::nullopt;
  residual = (a * s - b).norm();
  return FocalDepth{s(0), s(1)};
}

}  // namespace

Result<TsaiViewResult> tsai_calibrate_view(const PlanarView& view, const TsaiCamera& sensor,
                                           std::optional<double> known_f_mm) {
  const std::size_t n = view.uv_px.size();
  if (n != view.board_mm.size())
    return Error::make(Errc::invalid_argument, "tsai: %zu image points for %zu target points", n,
                       view.board_mm.size());
  if (n < 6) return Error::make(Errc::degenerate, "tsai: %zu points, need at least 6", n);
  if (!(sensor.dx_mm > 0 && sensor.dy_mm > 0 && sensor.sx > 0))
    return Error::make(Errc::non_positive, "tsai: pixel pitch and sx must be > 0");

  // Distorted sensor coordinates (mm) from the given sensor geometry.
  std::vector<Eigen::Vector2d> pd(n);
  for (std::size_t k = 0; k < n; ++k) pd[k] = pixel_to_sensor(sensor, view.uv_px[k]);

  // Step 1: [-Yd xw, -Yd yw, -Yd, Xd xw, Xd yw, Xd] . (r1 r2 tx r4 r5 ty) = 0,
  // columns scaled to comparable size for the SVD.
  double sw = 0, sp = 0;
  for (std::size_t k = 0; k < n; ++k) {
    sw += view.board_mm[k].squaredNorm();
    sp += pd[k].squaredNorm();
  }
  sw = std::sqrt(sw / static_cast<double>(n));
  sp = std::sqrt(sp / static_cast<double>(n));
  if (!(sw > 0 && sp > 0)) return Error::make(Errc::degenerate, "tsai: all points coincide");
  Eigen::Matrix<double, Eigen::Dynamic, 6> m(static_cast<Eigen::Index>(n), 6);
  for (std::size_t k = 0; k < n; ++k) {
    const double xw = view.board_mm[k].x() / sw, yw = view.board_mm[k].y() / sw;
    const double xd = pd[k].x() / sp, yd = pd[k].y() / sp;
    m.row(static_cast<Eigen::Index>(k)) << -yd * xw, -yd * yw, -yd, xd * xw, xd * yw, xd;
  }
  const Eigen::Matrix<double, 6, 6> normal = m.transpose() * m;
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>> eig(normal);
  const Eigen::Matrix<double, 6, 1> ev = eig.eigenvalues();  // ascending
  if (!(ev(1) > 1e-12 * ev(5)))
    return Error::make(Errc::degenerate, "tsai: radial alignment is singular (points collinear?)");
  const Eigen::Matrix<double, 6, 1> v = eig.eigenvectors().col(0);
  // Undo the column scaling: rotation entries were multiplied by sw, translations not.
  double r1 = v(0), r2 = v(1), tx = v(2) * sw, r4 = v(3), r5 = v(4), ty = v(5) * sw;
  Eigen::Matrix2d c;
  c << r1, r2, r4, r5;
  const double scale = Eigen::JacobiSVD<Eigen::Matrix2d>(c).singularValues()(0);
  if (!(scale > 0)) return Error::make(Errc::degenerate, "tsai: radial alignment gave no rotation");
  r1 /= scale, r2 /= scale, tx /= scale, r4 /= scale, r5 /= scale, ty /= scale;
  // Sign: Xc, Yc have the signs of Xd, Yd.
  double agree = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const double xw = view.board_mm[k].x(), yw = view.board_mm[k].y();
    agree += (r1 * xw + r2 * yw + tx) * pd[k].x() + (r4 * xw + r5 * yw + ty) * pd[k].y();
  }
  if (agree < 0) r1 = -r1, r2 = -r2, tx = -tx, r4 = -r4, r5 = -r5, ty = -ty;

  // Two rotations fit step 1 (r3, r6 and the third row change sign). Without
  // f, the wrong one gives f < 0; with f given, it fits step 2's equations worse.
  std::optional<FocalDepth> fd;
  Eigen::Matrix3d rot = Eigen::Matrix3d::Identity();
  double best_residual = 0;
  for (int root = 0; root < 2; ++root) {
    const double r3 = std::sqrt(std::max(0.0, 1 - r1 * r1 - r2 * r2)) * (root == 0 ? 1 : -1);
    const double s6 = (r1 * r4 + r2 * r5) > 0 ? -1.0 : 1.0;
    const double r6 = s6 * std::sqrt(std::max(0.0, 1 - r4 * r4 - r5 * r5)) * (root == 0 ? 1 : -1);
    Eigen::Matrix3d raw;
    raw.row(0) << r1, r2, r3;
    raw.row(1) << r4, r5, r6;
    raw.row(2) = raw.row(0).cross(raw.row(1));
    const Eigen::Matrix3d candidate = nearest_rotation(raw);
    const double tilt = std::acos(std::min(1.0, std::abs(candidate(2, 2)))) * kRadToDeg;
    if (!known_f_mm && tilt < kMinTiltDeg)
      return Error::make(
          Errc::degenerate,
          "view nearly parallel to the image (tilt %.1f deg < %.0f): f and distance not "
          "separable",
          tilt, kMinTiltDeg);
    double residual = 0;
    const auto sol = solve_f_tz(candidate, tx, ty, pd, view, known_f_mm, residual);
    if (!sol || !(sol->f > 0) || !(sol->tz > 0)) continue;
    if (!fd || residual < best_residual) {
      fd = sol;
      rot = candidate;
      best_residual = residual;
    }
  }
  if (!fd)
    return Error::make(Errc::no_solution, "tsai: no focal length > 0 in front of the camera");

  TsaiViewResult out;
  out.camera = sensor;
  out.camera.R = rot;
  out.camera.T_mm = Eigen::Vector3d(tx, ty, fd->tz);
  out.camera.f_mm = fd->f;
  out.camera.kappa1 = 0;
  out.tilt_deg = std::acos(std::min(1.0, std::abs(rot(2, 2)))) * kRadToDeg;

  // Step 3: f, tz, kappa1 by Levenberg-Marquardt (numeric Jacobian: 3 unknowns);
  // with f given, tz and kappa1 only.
  const bool fit_f = !known_f_mm.has_value();
  auto camera_at = [&](const Eigen::VectorXd& x) {
    TsaiCamera cam = out.camera;
    cam.T_mm.z() = x(0);
    cam.kappa1 = x(1);
    if (fit_f) cam.f_mm = x(2);
    return cam;
  };
  auto residuals = [&](const Eigen::VectorXd& x, Eigen::VectorXd& r) {
    const TsaiCamera cam = camera_at(x);
    r.resize(static_cast<Eigen::Index>(2 * n));
    for (std::size_t k = 0; k < n; ++k) {
      auto uv = project(cam, Eigen::Vector3d(view.board_mm[k].x(), view.board_mm[k].y(), 0));
      if (!uv) return false;
      r.segment<2>(static_cast<Eigen::Index>(2 * k)) = *uv - view.uv_px[k];
    }
    return true;
  };
  // kappa1 is scaled so that a unit change moves an image corner by about a pixel.
  const double r_max = std::hypot(sensor.width * sensor.dx_mm, sensor.height * sensor.dy_mm) / 2;
  const double kappa_unit = 1.0 / (r_max * r_max * r_max / sensor.dy_mm);
  LmProblem problem;
  problem.cost = [&](const Eigen::VectorXd& x, double& cost) {
    Eigen::VectorXd r;
    Eigen::VectorXd xs = x;
    xs(1) *= kappa_unit;
    if (!residuals(xs, r)) return false;
    cost = 0.5 * r.squaredNorm();
    return true;
  };
  problem.linearise = [&](const Eigen::VectorXd& x, Eigen::MatrixXd& jtj, Eigen::VectorXd& jtr,
                          double& cost) {
    Eigen::VectorXd r0, rp, rm;
    Eigen::VectorXd xs = x;
    xs(1) *= kappa_unit;
    if (!residuals(xs, r0)) return false;
    cost = 0.5 * r0.squaredNorm();
    Eigen::MatrixXd j(r0.size(), x.size());
    for (Eigen::Index p = 0; p < x.size(); ++p) {
      const double h = 1e-6 * std::max(1.0, std::abs(x(p)));
      Eigen::VectorXd xp = xs, xm = xs;
      xp(p) += p == 1 ? h * kappa_unit : h;
      xm(p) -= p == 1 ? h * kappa_unit : h;
      if (!residuals(xp, rp) || !residuals(xm, rm)) return false;
      j.col(p) = (rp - rm) / (2 * h);
    }
    jtj = j.transpose() * j;
    jtr = j.transpose() * r0;
    return true;
  };
  Eigen::VectorXd x(fit_f ? 3 : 2);
  x(0) = out.camera.T_mm.z();
  x(1) = 0;
  if (fit_f) x(2) = out.camera.f_mm;
  const LmReport rep = minimise(problem, x, {});
  if (rep.valid) {
    x(1) *= kappa_unit;
    out.camera = camera_at(x);
  }
  bool ok = true;
  out.rms_px = reprojection_rms(out.camera, view, ok);
  if (!ok || !(out.camera.f_mm > 0))
    return Error::make(Errc::no_solution, "tsai: refinement left the camera model's domain");
  return out;
}

}  // namespace petra::calib
