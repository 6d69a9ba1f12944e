#include "sim/calib/camera_calibration.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "sim/calib/format_text.hpp"

namespace petra::calib {

namespace {

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

std::string view_name(const PlanarView& v, std::size_t index) {
  return v.name.empty() ? format_text("view %zu", index) : v.name;
}

double mean_distance(const PlanarView& a, const PlanarView& b) {
  double s = 0;
  for (std::size_t k = 0; k < a.uv_px.size(); ++k) s += (a.uv_px[k] - b.uv_px[k]).norm();
  return s / static_cast<double>(a.uv_px.size());
}

}  // namespace

Result<CameraCalibration> calibrate_camera(const std::vector<PlanarView>& views,
                                           const TsaiCamera& sensor,
                                           const CameraCalibOptions& opt) {
  if (sensor.width <= 0 || sensor.height <= 0 || !(sensor.dx_mm > 0) || !(sensor.dy_mm > 0))
    return Error::make(Errc::invalid_argument,
                       "calibrate: sensor size and pixel pitch must be > 0");
  CameraCalibration out;
  // 1. Duplicates.
  std::vector<std::size_t> distinct;
  for (std::size_t v = 0; v < views.size(); ++v) {
    if (views[v].uv_px.size() != views[v].board_mm.size() || views[v].uv_px.empty())
      return Error::make(Errc::invalid_argument, "calibrate: %s has no or unmatched points",
                         view_name(views[v], v).c_str());
    bool dup = false;
    for (std::size_t d : distinct)
      if (views[d].uv_px.size() == views[v].uv_px.size() &&
          mean_distance(views[d], views[v]) < opt.duplicate_px) {
        out.notes.push_back(
            format_text("%s: same board position as %s (corners within %.2f px), ignored",
                        view_name(views[v], v).c_str(), view_name(views[d], d).c_str(),
                        mean_distance(views[d], views[v])));
        dup = true;
        break;
      }
    if (!dup) distinct.push_back(v);
  }
  if (static_cast<int>(distinct.size()) < opt.min_views)
    return Error::make(Errc::degenerate,
                       "calibrate: %zu distinct views of the board, need at least %d",
                       distinct.size(), opt.min_views);

  // 2. Tsai on each view, centre at the image centre and sx = 1 (or as given).
  TsaiCamera start = sensor;
  start.cx_px = (sensor.width - 1) / 2.0;
  start.cy_px = (sensor.height - 1) / 2.0;
  if (opt.estimate_sx) start.sx = 1.0;
  std::vector<double> fs, kappas;
  double max_tilt = 0;
  for (std::size_t v : distinct) {
    auto r = tsai_calibrate_view(views[v], start);
    if (r) {
      fs.push_back(r->camera.f_mm);
      kappas.push_back(r->camera.kappa1);
      max_tilt = std::max(max_tilt, r->tilt_deg);
    } else if (r.code() == Errc::degenerate) {
      out.notes.push_back(format_text("%s: %s", view_name(views[v], v).c_str(), r.error().message));
    }
  }
  if (fs.empty())
    return Error::make(Errc::degenerate,
                       "calibrate: no view tilted enough (>= %.0f deg) to give the focal length; "
                       "tilt the board 20-45 deg",
                       kMinTiltDeg);
  start.f_mm = median(fs);
  start.kappa1 = median(kappas);

  // 3. Poses with the common f.
  Bundle b;
  b.cameras = {start};
  b.rig = {Pose{}};
  IntrinsicsMask mask;
  mask.sx = opt.estimate_sx;
  mask.centre = opt.estimate_centre;
  b.free = {mask};
  for (std::size_t v : distinct) {
    auto r = tsai_calibrate_view(views[v], start, start.f_mm);
    if (!r) {
      out.notes.push_back(format_text("%s: no pose (%s), ignored", view_name(views[v], v).c_str(),
                                      r.error().message));
      continue;
    }
    const int index = static_cast<int>(b.views.size());
    b.views.push_back({r->camera.R, r->camera.T_mm});
    out.views.push_back(static_cast<int>(v));
    for (std::size_t k = 0; k < views[v].uv_px.size(); ++k)
      b.observations.push_back(
          {0, index, Eigen::Vector3d(views[v].board_mm[k].x(), views[v].board_mm[k].y(), 0),
           views[v].uv_px[k]});
  }
  if (static_cast<int>(out.views.size()) < opt.min_views)
    return Error::make(Errc::degenerate, "calibrate: %zu usable views, need at least %d",
                       out.views.size(), opt.min_views);

  // 4. Joint refinement; fix what the views do not determine.
  const Bundle initial = b;
  auto fit = refine_bundle(b);
  if (!fit) return fit.error();
  const auto& s = fit->sigma[0];
  const bool centre_weak =
      mask.centre && !(s[kCx] < opt.max_centre_sigma_px && s[kCy] < opt.max_centre_sigma_px);
  const bool sx_weak = mask.sx && !(s[kSx] < opt.max_sx_sigma);
  if (centre_weak || sx_weak) {
    if (centre_weak)
      out.notes.push_back(
          format_text("principal point not determined by these views (sigma %.3g, %.3g px): "
                      "fixed at the image centre",
                      s[kCx], s[kCy]));
    if (sx_weak)
      out.notes.push_back(
          format_text("sx not determined by these views (sigma %.3g): fixed at 1", s[kSx]));
    b = initial;
    b.free[0].centre = mask.centre && !centre_weak;
    b.free[0].sx = mask.sx && !sx_weak;
    fit = refine_bundle(b);
    if (!fit) return fit.error();
  }
  if (!(fit->sigma[0][kF] < 0.1 * b.cameras[0].f_mm))
    return Error::make(Errc::degenerate,
                       "calibrate: focal length not determined by these views (sigma %.3g mm)",
                       fit->sigma[0][kF]);
  out.camera = b.cameras[0];
  out.camera.R = Eigen::Matrix3d::Identity();
  out.camera.T_mm = Eigen::Vector3d::Zero();
  out.estimated = b.free[0];
  out.poses = b.views;
  out.rms_px = fit->rms_px;
  out.sigma = fit->sigma[0];
  out.view_rms_px.assign(b.views.size(), 0.0);
  std::vector<int> count(b.views.size(), 0);
  for (std::size_t k = 0; k < b.observations.size(); ++k) {
    const auto v = static_cast<std::size_t>(b.observations[k].view);
    out.view_rms_px[v] += fit->residuals_px[k].squaredNorm();
    ++count[v];
  }
  for (std::size_t v = 0; v < out.view_rms_px.size(); ++v)
    out.view_rms_px[v] = std::sqrt(out.view_rms_px[v] / count[v]);
  return out;
}

}  // namespace petra::calib
