#include "sim/calib/calib_bundle.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <limits>

namespace petra::calib {

namespace {

constexpr int kPoseParams = 6;

Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
}

Eigen::Matrix3d exp_so3(const Eigen::Vector3d& w) {
  const double a = w.norm();
  if (a < 1e-300) return Eigen::Matrix3d::Identity();
  return Eigen::AngleAxisd(a, w / a).toRotationMatrix();
}

Eigen::Vector3d log_so3(const Eigen::Matrix3d& r) {
  const Eigen::AngleAxisd aa(r);
  return aa.angle() * aa.axis();
}

// State layout: cameras (5 each), rig poses 1..K-1 (6 each), views (6 each).
struct Layout {
  int cameras = 0, views = 0;
  int rig_offset() const { return kIntrinsicCount * cameras; }
  int view_offset() const { return rig_offset() + kPoseParams * (cameras - 1); }
  int size() const { return view_offset() + kPoseParams * views; }
};

Eigen::VectorXd pack(const Bundle& b, const Layout& l) {
  Eigen::VectorXd x(l.size());
  for (int c = 0; c < l.cameras; ++c) {
    const TsaiCamera& cam = b.cameras[static_cast<std::size_t>(c)];
    x.segment<kIntrinsicCount>(kIntrinsicCount * c) << cam.f_mm, cam.kappa1, cam.cx_px, cam.cy_px,
        cam.sx;
  }
  for (int k = 1; k < l.cameras; ++k) {
    const Pose& p = b.rig[static_cast<std::size_t>(k)];
    x.segment<3>(l.rig_offset() + kPoseParams * (k - 1)) = log_so3(p.R);
    x.segment<3>(l.rig_offset() + kPoseParams * (k - 1) + 3) = p.T;
  }
  for (int v = 0; v < l.views; ++v) {
    const Pose& p = b.views[static_cast<std::size_t>(v)];
    x.segment<3>(l.view_offset() + kPoseParams * v) = log_so3(p.R);
    x.segment<3>(l.view_offset() + kPoseParams * v + 3) = p.T;
  }
  return x;
}

void unpack(const Eigen::VectorXd& x, const Layout& l, Bundle& b) {
  for (int c = 0; c < l.cameras; ++c) {
    TsaiCamera& cam = b.cameras[static_cast<std::size_t>(c)];
    const int o = kIntrinsicCount * c;
    cam.f_mm = x(o + kF);
    cam.kappa1 = x(o + kKappa1);
    cam.cx_px = x(o + kCx);
    cam.cy_px = x(o + kCy);
    cam.sx = x(o + kSx);
  }
  for (int k = 1; k < l.cameras; ++k) {
    Pose& p = b.rig[static_cast<std::size_t>(k)];
    p.R = exp_so3(x.segment<3>(l.rig_offset() + kPoseParams * (k - 1)));
    p.T = x.segment<3>(l.rig_offset() + kPoseParams * (k - 1) + 3);
  }
  for (int v = 0; v < l.views; ++v) {
    Pose& p = b.views[static_cast<std::size_t>(v)];
    p.R = exp_so3(x.segment<3>(l.view_offset() + kPoseParams * v));
    p.T = x.segment<3>(l.view_offset() + kPoseParams * v + 3);
  }
}

// Column of each state entry in the free-parameter system, or -1 when fixed.
std::vector<int> free_columns(const Bundle& b, const Layout& l, int& count) {
  std::vector<int> col(static_cast<std::size_t>(l.size()), -1);
  count = 0;
  for (int c = 0; c < l.cameras; ++c) {
    const IntrinsicsMask& m = b.free[static_cast<std::size_t>(c)];
    const bool is_free[kIntrinsicCount] = {m.f, m.kappa1, m.centre, m.centre, m.sx};
    for (int k = 0; k < kIntrinsicCount; ++k)
      if (is_free[k]) col[static_cast<std::size_t>(kIntrinsicCount * c + k)] = count++;
  }
  for (int k = l.rig_offset(); k < l.size(); ++k) col[static_cast<std::size_t>(k)] = count++;
  return col;
}

struct Projection {
  Eigen::Vector2d uv;
  // d uv / d (f, kappa1, cx, cy, sx), d uv / d (view rotation, view translation),
  // d uv / d (rig rotation, rig translation)
  Eigen::Matrix<double, 2, kIntrinsicCount> d_intr;
  Eigen::Matrix<double, 2, 6> d_view;
  Eigen::Matrix<double, 2, 6> d_rig;
};

bool project_obs(const TsaiCamera& cam, const Pose& rig, bool has_rig, const Pose& view,
                 const Eigen::Vector3d& pw, bool jacobians, Projection& out) {
  const Eigen::Vector3d qp = view.R * pw;
  const Eigen::Vector3d p0 = qp + view.T;
  const Eigen::Vector3d pc = has_rig ? Eigen::Vector3d(rig.R * p0 + rig.T) : p0;
  if (!(pc.z() > 0)) return false;
  const double iz = 1.0 / pc.z();
  const Eigen::Vector2d xn(pc.x() * iz, pc.y() * iz);
  const Eigen::Vector2d pu = cam.f_mm * xn;
  auto pd_r = distort_sensor(cam.kappa1, pu);
  if (!pd_r) return false;
  const Eigen::Vector2d pd = *pd_r;
  out.uv = sensor_to_pixel(cam, pd);
  if (!jacobians) return true;
  const double rd2 = pd.squaredNorm();
  Eigen::Matrix2d a = (1.0 + cam.kappa1 * rd2) * Eigen::Matrix2d::Identity() +
                      2.0 * cam.kappa1 * pd * pd.transpose();
  const Eigen::Matrix2d ainv = a.inverse();
  const Eigen::Matrix2d d_pix = Eigen::Vector2d(cam.sx / cam.dx_mm, 1.0 / cam.dy_mm).asDiagonal();
  const Eigen::Matrix2d d_pu = d_pix * ainv;  // d uv / d Pu
  Eigen::Matrix<double, 2, 3> d_pc;
  d_pc << 1, 0, -xn.x(), 0, 1, -xn.y();
  d_pc *= cam.f_mm * iz;
  const Eigen::Matrix<double, 2, 3> m = d_pu * d_pc;  // d uv / d Pc
  out.d_intr.col(kF) = d_pu * xn;
  out.d_intr.col(kKappa1) = -d_pu * pd * rd2;
  out.d_intr.col(kCx) = Eigen::Vector2d(1, 0);
  out.d_intr.col(kCy) = Eigen::Vector2d(0, 1);
  out.d_intr.col(kSx) = Eigen::Vector2d(pd.x() / cam.dx_mm, 0);
  const Eigen::Matrix<double, 2, 3> m0 =
      has_rig ? Eigen::Matrix<double, 2, 3>(m * rig.R) : m;  // d uv / d P0
  out.d_view.leftCols<3>() = -m0 * skew(qp);
  out.d_view.rightCols<3>() = m0;
  if (has_rig) {
    out.d_rig.leftCols<3>() = -m * skew(rig.R * p0);
    out.d_rig.rightCols<3>() = m;
  }
  return true;
}

bool check_indices(const Bundle& b) {
  for (const BundleObservation& o : b.observations)
    if (o.camera < 0 || o.camera >= static_cast<int>(b.cameras.size()) || o.view < 0 ||
        o.view >= static_cast<int>(b.views.size()))
      return false;
  return b.free.size() == b.cameras.size() && b.rig.size() == b.cameras.size();
}

}  // namespace

Result<std::vector<Eigen::Vector2d>> bundle_residuals(const Bundle& b) {
  if (!check_indices(b))
    return Error::make(Errc::invalid_argument, "bundle: inconsistent sizes or indices");
  std::vector<Eigen::Vector2d> out;
  out.reserve(b.observations.size());
  Projection p;
  for (const BundleObservation& o : b.observations) {
    const auto c = static_cast<std::size_t>(o.camera);
    if (!project_obs(b.cameras[c], b.rig[c], o.camera > 0,
                     b.views[static_cast<std::size_t>(o.view)], o.board_mm, false, p))
      return Error::make(Errc::no_solution, "bundle: view %d not in front of camera %d", o.view,
                         o.camera);
    out.push_back(p.uv - o.uv_px);
  }
  return out;
}

Result<BundleFit> refine_bundle(Bundle& b, const LmOptions& options) {
  if (!check_indices(b))
    return Error::make(Errc::invalid_argument, "bundle: inconsistent sizes or indices");
  const Layout layout{static_cast<int>(b.cameras.size()), static_cast<int>(b.views.size())};
  int n_free = 0;
  const std::vector<int> col = free_columns(b, layout, n_free);
  const long n_res = 2 * static_cast<long>(b.observations.size());
  if (n_res <= n_free)
    return Error::make(Errc::degenerate, "bundle: %ld residuals for %d parameters", n_res, n_free);
  Bundle work = b;

  auto evaluate = [&](const Eigen::VectorXd& x, Eigen::MatrixXd* jtj, Eigen::VectorXd* jtr,
                      double& cost) {
    unpack(x, layout, work);
    if (jtj) {
      jtj->setZero(n_free, n_free);
      jtr->setZero(n_free);
    }
    cost = 0;
    Projection p;
    int idx[kIntrinsicCount + 12];
    Eigen::Matrix<double, 2, kIntrinsicCount + 12> jl;
    for (const BundleObservation& o : work.observations) {
      const auto c = static_cast<std::size_t>(o.camera);
      if (!project_obs(work.cameras[c], work.rig[c], o.camera > 0,
                       work.views[static_cast<std::size_t>(o.view)], o.board_mm, jtj != nullptr, p))
        return false;
      const Eigen::Vector2d r = p.uv - o.uv_px;
      cost += 0.5 * r.squaredNorm();
      if (!jtj) continue;
      int m = 0;
      for (int k = 0; k < kIntrinsicCount; ++k) {
        const int cc = col[static_cast<std::size_t>(kIntrinsicCount * o.camera + k)];
        if (cc < 0) continue;
        idx[m] = cc;
        jl.col(m++) = p.d_intr.col(k);
      }
      for (int k = 0; k < kPoseParams; ++k) {
        idx[m] = col[static_cast<std::size_t>(layout.view_offset() + kPoseParams * o.view + k)];
        jl.col(m++) = p.d_view.col(k);
      }
      if (o.camera > 0)
        for (int k = 0; k < kPoseParams; ++k) {
          idx[m] =
              col[static_cast<std::size_t>(layout.rig_offset() + kPoseParams * (o.camera - 1) + k)];
          jl.col(m++) = p.d_rig.col(k);
        }
      for (int a = 0; a < m; ++a) {
        (*jtr)(idx[a]) += jl.col(a).dot(r);
        for (int bb = 0; bb < m; ++bb) (*jtj)(idx[a], idx[bb]) += jl.col(a).dot(jl.col(bb));
      }
    }
    return true;
  };

  // The free-parameter step maps back onto the state; rotations compose.
  auto plus = [&](const Eigen::VectorXd& x, const Eigen::VectorXd& delta) {
    Eigen::VectorXd y = x;
    for (int k = 0; k < layout.rig_offset(); ++k)
      if (col[static_cast<std::size_t>(k)] >= 0) y(k) += delta(col[static_cast<std::size_t>(k)]);
    for (int o = layout.rig_offset(); o < layout.size(); o += kPoseParams) {
      const int c0 = col[static_cast<std::size_t>(o)];
      y.segment<3>(o) = log_so3(exp_so3(delta.segment<3>(c0)) * exp_so3(x.segment<3>(o)));
      y.segment<3>(o + 3) += delta.segment<3>(c0 + 3);
    }
    return y;
  };

  LmProblem problem;
  problem.linearise = [&](const Eigen::VectorXd& x, Eigen::MatrixXd& jtj, Eigen::VectorXd& jtr,
                          double& cost) { return evaluate(x, &jtj, &jtr, cost); };
  problem.cost = [&](const Eigen::VectorXd& x, double& cost) {
    return evaluate(x, nullptr, nullptr, cost);
  };
  problem.plus = plus;

  Eigen::VectorXd x = pack(b, layout);
  const LmReport rep = minimise(problem, x, options);
  if (!rep.valid)
    return Error::make(Errc::no_solution, "bundle: start point outside the camera model's domain");
  unpack(x, layout, b);

  BundleFit fit;
  fit.iterations = rep.iterations;
  auto res = bundle_residuals(b);
  if (!res) return res.error();
  fit.residuals_px = std::move(*res);
  double ss = 0;
  for (const Eigen::Vector2d& r : fit.residuals_px) ss += r.squaredNorm();
  fit.rms_px = std::sqrt(ss / static_cast<double>(fit.residuals_px.size()));

  // Covariance sigma^2 (J^T J)^-1 with sigma^2 from the residuals. The normal
  // matrix is scaled to unit diagonal so that "singular" means the same for
  // millimetres and pixels.
  const double sigma2 = ss / static_cast<double>(n_res - n_free);
  Eigen::VectorXd d = rep.jtj.diagonal().cwiseMax(1e-300).cwiseSqrt().cwiseInverse();
  const Eigen::MatrixXd scaled = d.asDiagonal() * rep.jtj * d.asDiagonal();
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(scaled);
  const Eigen::VectorXd ev = eig.eigenvalues();
  const double ev_max = ev.maxCoeff();
  Eigen::VectorXd var = Eigen::VectorXd::Zero(n_free);
  std::vector<bool> undetermined(static_cast<std::size_t>(n_free), false);
  for (Eigen::Index k = 0; k < ev.size(); ++k) {
    const Eigen::VectorXd v = eig.eigenvectors().col(k);
    if (ev(k) <= 1e-12 * ev_max) {
      for (Eigen::Index p = 0; p < n_free; ++p)
        if (std::abs(v(p)) > 1e-3) undetermined[static_cast<std::size_t>(p)] = true;
      continue;
    }
    var += v.cwiseAbs2() / ev(k);
  }
  fit.sigma.resize(b.cameras.size());
  for (std::size_t c = 0; c < b.cameras.size(); ++c)
    for (int k = 0; k < kIntrinsicCount; ++k) {
      const int cc = col[c * kIntrinsicCount + static_cast<std::size_t>(k)];
      if (cc < 0)
        fit.sigma[c][static_cast<std::size_t>(k)] = 0;
      else if (undetermined[static_cast<std::size_t>(cc)])
        fit.sigma[c][static_cast<std::size_t>(k)] = std::numeric_limits<double>::infinity();
      else
        fit.sigma[c][static_cast<std::size_t>(k)] = std::sqrt(sigma2 * var(cc)) * d(cc);
    }
  return fit;
}

}  // namespace petra::calib
