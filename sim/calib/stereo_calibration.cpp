#include "sim/calib/stereo_calibration.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "sim/calib/format_text.hpp"

namespace petra::calib {

namespace {

PlanarView make_view(const std::vector<Eigen::Vector2d>& uv, const std::string& name,
                     const StereoCalibOptions& o) {
  PlanarView v;
  v.name = name;
  v.uv_px = uv;
  for (int j = 0; j < o.rows; ++j)
    for (int i = 0; i < o.cols; ++i) v.board_mm.emplace_back(i * o.square_mm, j * o.square_mm);
  return v;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// Chordal mean of rotations: the rotation nearest to their sum.
Eigen::Matrix3d mean_rotation(const std::vector<Eigen::Matrix3d>& rs) {
  Eigen::Matrix3d sum = Eigen::Matrix3d::Zero();
  for (const Eigen::Matrix3d& r : rs) sum += r;
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(sum, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d u = svd.matrixU();
  if ((u * svd.matrixV().transpose()).determinant() < 0) u.col(2) *= -1;
  return u * svd.matrixV().transpose();
}

int position(const std::vector<int>& v, int x) {
  const auto it = std::find(v.begin(), v.end(), x);
  return it == v.end() ? -1 : static_cast<int>(it - v.begin());
}

}  // namespace

Result<StereoCalibration> calibrate_stereo(const std::vector<StereoPairCorners>& pairs,
                                           const StereoCalibOptions& o) {
  if (o.cols < 2 || o.rows < 2)
    return Error::make(Errc::invalid_argument, "stereo: board %dx%d", o.cols, o.rows);
  if (!(o.square_mm > 0)) return Error::make(Errc::non_positive, "stereo: square size must be > 0");
  const std::size_t n_corners = static_cast<std::size_t>(o.cols) * o.rows;
  StereoCalibration out;

  // Each camera on its own, over every image in which it saw the board.
  std::vector<PlanarView> lv, rv;
  std::vector<int> l_pair, r_pair;  // input pair of each view
  for (std::size_t p = 0; p < pairs.size(); ++p) {
    const StereoPairCorners& pc = pairs[p];
    if (!pc.left_uv.empty()) {
      if (pc.left_uv.size() != n_corners)
        return Error::make(Errc::invalid_argument, "stereo: %s has %zu corners, board has %zu",
                           pc.left_name.c_str(), pc.left_uv.size(), n_corners);
      lv.push_back(make_view(pc.left_uv, pc.left_name, o));
      l_pair.push_back(static_cast<int>(p));
    }
    if (!pc.right_uv.empty()) {
      if (pc.right_uv.size() != n_corners)
        return Error::make(Errc::invalid_argument, "stereo: %s has %zu corners, board has %zu",
                           pc.right_name.c_str(), pc.right_uv.size(), n_corners);
      rv.push_back(make_view(pc.right_uv, pc.right_name, o));
      r_pair.push_back(static_cast<int>(p));
    }
  }
  if (static_cast<int>(lv.size()) < o.camera.min_views ||
      static_cast<int>(rv.size()) < o.camera.min_views)
    return Error::make(
        Errc::degenerate,
        "the board was found in %zu left and %zu right images of %zu pairs, need at least %d each",
        lv.size(), rv.size(), pairs.size(), o.camera.min_views);
  auto left = calibrate_camera(lv, o.left_sensor, o.camera);
  if (!left) return Error::make(left.code(), "left camera: %s", left.error().message);
  auto right = calibrate_camera(rv, o.right_sensor, o.camera);
  if (!right) return Error::make(right.code(), "right camera: %s", right.error().message);
  for (const std::string& n : left->notes) out.notes.push_back("left camera: " + n);
  for (const std::string& n : right->notes) out.notes.push_back("right camera: " + n);

  // Pairs used by both single-camera fits give the rig.
  std::vector<int> l_used, r_used;  // input pair of each used view
  for (int v : left->views) l_used.push_back(l_pair[static_cast<std::size_t>(v)]);
  for (int v : right->views) r_used.push_back(r_pair[static_cast<std::size_t>(v)]);
  std::vector<Eigen::Matrix3d> rel_r;
  std::vector<double> tx, ty, tz;
  for (std::size_t a = 0; a < l_used.size(); ++a) {
    const int b = position(r_used, l_used[a]);
    if (b < 0) continue;
    const Pose& pl = left->poses[a];
    const Pose& pr = right->poses[static_cast<std::size_t>(b)];
    const Eigen::Matrix3d r = pr.R * pl.R.transpose();
    const Eigen::Vector3d t = pr.T - r * pl.T;
    rel_r.push_back(r);
    tx.push_back(t.x());
    ty.push_back(t.y());
    tz.push_back(t.z());
    out.pairs.push_back(l_used[a]);
  }
  if (static_cast<int>(out.pairs.size()) < o.min_pairs)
    return Error::make(Errc::degenerate,
                       "stereo: the board is in both images of %zu usable pairs, need at least %d",
                       out.pairs.size(), o.min_pairs);
  Pose rig;
  rig.R = mean_rotation(rel_r);
  rig.T = Eigen::Vector3d(median(tx), median(ty), median(tz));

  // Joint refinement: views are the input pairs seen by either camera.
  Bundle b;
  b.cameras = {left->camera, right->camera};
  b.free = {left->estimated, right->estimated};
  b.rig = {Pose{}, rig};
  std::vector<int> view_pair;
  for (std::size_t p = 0; p < pairs.size(); ++p) {
    const int a = position(l_used, static_cast<int>(p));
    const int c = position(r_used, static_cast<int>(p));
    if (a < 0 && c < 0) continue;
    Pose pose;
    if (a >= 0) {
      pose = left->poses[static_cast<std::size_t>(a)];
    } else {  // right only: board -> left = rig^-1 * (board -> right)
      const Pose& pr = right->poses[static_cast<std::size_t>(c)];
      pose.R = rig.R.transpose() * pr.R;
      pose.T = rig.R.transpose() * (pr.T - rig.T);
    }
    const int view = static_cast<int>(b.views.size());
    b.views.push_back(pose);
    view_pair.push_back(static_cast<int>(p));
    for (int cam = 0; cam < 2; ++cam) {
      if ((cam == 0 ? a : c) < 0) continue;
      const std::vector<Eigen::Vector2d>& uv = cam == 0 ? pairs[p].left_uv : pairs[p].right_uv;
      for (int j = 0; j < o.rows; ++j)
        for (int i = 0; i < o.cols; ++i)
          b.observations.push_back({cam, view, Eigen::Vector3d(i * o.square_mm, j * o.square_mm, 0),
                                    uv[static_cast<std::size_t>(j * o.cols + i)]});
    }
  }
  auto fit = refine_bundle(b);
  if (!fit) return Error::make(fit.code(), "stereo: %s", fit.error().message);

  // Per-image and per-camera RMS of the joint model.
  out.left_rms_px.assign(pairs.size(), -1.0);
  out.right_rms_px.assign(pairs.size(), -1.0);
  std::vector<double> ss[2] = {std::vector<double>(pairs.size(), 0.0),
                               std::vector<double>(pairs.size(), 0.0)};
  std::vector<int> cnt[2] = {std::vector<int>(pairs.size(), 0), std::vector<int>(pairs.size(), 0)};
  double cam_ss[2] = {0, 0};
  int cam_n[2] = {0, 0};
  for (std::size_t k = 0; k < b.observations.size(); ++k) {
    const BundleObservation& ob = b.observations[k];
    const auto p = static_cast<std::size_t>(view_pair[static_cast<std::size_t>(ob.view)]);
    const double e2 = fit->residuals_px[k].squaredNorm();
    ss[ob.camera][p] += e2;
    ++cnt[ob.camera][p];
    cam_ss[ob.camera] += e2;
    ++cam_n[ob.camera];
  }
  for (std::size_t p = 0; p < pairs.size(); ++p) {
    if (cnt[0][p]) out.left_rms_px[p] = std::sqrt(ss[0][p] / cnt[0][p]);
    if (cnt[1][p]) out.right_rms_px[p] = std::sqrt(ss[1][p] / cnt[1][p]);
  }
  out.left_rms_px_all = std::sqrt(cam_ss[0] / std::max(1, cam_n[0]));
  out.right_rms_px_all = std::sqrt(cam_ss[1] / std::max(1, cam_n[1]));
  out.rms_px = fit->rms_px;
  out.left_sigma = fit->sigma[0];
  out.right_sigma = fit->sigma[1];

  // World frame.
  Pose world_to_left;  // identity: world = left camera
  if (o.world_at_target) {
    out.world_pair = out.pairs.front();
    world_to_left = b.views[static_cast<std::size_t>(position(view_pair, out.world_pair))];
  }
  TsaiCamera& l = out.rig.left;
  TsaiCamera& r = out.rig.right;
  l = b.cameras[0];
  r = b.cameras[1];
  l.R = world_to_left.R;
  l.T_mm = world_to_left.T;
  r.R = b.rig[1].R * world_to_left.R;
  r.T_mm = b.rig[1].R * world_to_left.T + b.rig[1].T;
  out.baseline_mm = b.rig[1].T.norm();  // right centre in the left frame is -R^T T
  out.left_alone = std::move(*left);
  out.right_alone = std::move(*right);
  if (auto s = validate(l, "left"); !s)
    return Error::make(s.code(), "stereo result: %s", s.error().message);
  if (auto s = validate(r, "right"); !s)
    return Error::make(s.code(), "stereo result: %s", s.error().message);
  return out;
}

}  // namespace petra::calib
