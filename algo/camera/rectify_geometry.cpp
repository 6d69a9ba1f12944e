#include "algo/camera/rectify_geometry.hpp"

#include <Eigen/Geometry>
#include <cmath>

namespace petra {

namespace {

// Direction (in the world frame) of the ray through the image centre.
Eigen::Vector3d centre_ray(const TsaiCamera& c) {
  return pixel_to_ray(c, {(c.width - 1) / 2.0, (c.height - 1) / 2.0}).direction;
}

}  // namespace

Result<RectifiedPair> rectify_geometry(const StereoRig& rig, int width, int height) {
  if (width <= 0 || height <= 0)
    return Error::make(Errc::non_positive, "rectify: output size %dx%d", width, height);
  const Eigen::Vector3d c1 = camera_centre_world(rig.left);
  const Eigen::Vector3d c2 = camera_centre_world(rig.right);
  const Eigen::Vector3d base = c2 - c1;
  const double b = base.norm();
  if (!(b > 1e-9)) return Error::make(Errc::degenerate, "rectify: camera centres coincide");
  // New x along the baseline; new z as close as possible to the mean optical
  // axis; y completes a right-handed frame (image rows point "down").
  const Eigen::Vector3d x = base / b;
  const Eigen::Vector3d mean_axis =
      (rig.left.R.row(2).transpose() + rig.right.R.row(2).transpose()).normalized();
  Eigen::Vector3d z = mean_axis - mean_axis.dot(x) * x;
  if (z.norm() < 1e-6)
    return Error::make(Errc::degenerate, "rectify: baseline along the optical axis");
  z.normalize();
  const Eigen::Vector3d y = z.cross(x);
  Eigen::Matrix3d R;
  R.row(0) = x.transpose();
  R.row(1) = y.transpose();
  R.row(2) = z.transpose();

  RectifiedPair pair;
  pair.baseline_mm = b;
  const double f = 0.5 * (rig.left.f_mm / rig.left.dy_mm + rig.right.f_mm / rig.right.dy_mm);
  // Centre the mean of both original image centres.
  const Eigen::Vector3d a1 = R * centre_ray(rig.left);
  const Eigen::Vector3d a2 = R * centre_ray(rig.right);
  const double mx = 0.5 * (a1.x() / a1.z() + a2.x() / a2.z());
  const double my = 0.5 * (a1.y() / a1.z() + a2.y() / a2.z());
  for (int k = 0; k < 2; ++k) {
    RectifiedCamera& rc = k == 0 ? pair.left : pair.right;
    const Eigen::Vector3d centre = k == 0 ? c1 : c2;
    rc.width = width;
    rc.height = height;
    rc.f_px = f;
    rc.cx_px = (width - 1) / 2.0 - f * mx;
    rc.cy_px = (height - 1) / 2.0 - f * my;
    rc.R = R;
    rc.T_mm = -(R * centre);
  }
  return pair;
}

Result<Eigen::Vector2d> rectified_to_original(const TsaiCamera& cam, const RectifiedCamera& rect,
                                              const Eigen::Vector2d& uv) {
  // Ray in the rectified frame, rotated into the original camera frame.
  const Eigen::Vector3d dir_rect((uv.x() - rect.cx_px) / rect.f_px,
                                 (uv.y() - rect.cy_px) / rect.f_px, 1.0);
  const Eigen::Vector3d dir_cam = cam.R * (rect.R.transpose() * dir_rect);
  if (!(dir_cam.z() > 0))
    return Error::make(Errc::out_of_range, "rectify: pixel (%.1f, %.1f) looks behind the camera",
                       uv.x(), uv.y());
  const Eigen::Vector2d pu(cam.f_mm * dir_cam.x() / dir_cam.z(),
                           cam.f_mm * dir_cam.y() / dir_cam.z());
  auto pd = distort_sensor(cam.kappa1, pu);
  if (!pd) return pd.error();
  return sensor_to_pixel(cam, *pd);
}

Result<Eigen::Vector2d> original_to_rectified(const TsaiCamera& cam, const RectifiedCamera& rect,
                                              const Eigen::Vector2d& uv) {
  const Eigen::Vector2d n = pixel_to_normalised(cam, uv);
  const Eigen::Vector3d dir = rect.R * (cam.R.transpose() * Eigen::Vector3d(n.x(), n.y(), 1.0));
  if (!(dir.z() > 0))
    return Error::make(Errc::out_of_range,
                       "rectify: pixel (%.1f, %.1f) maps behind the rectified camera", uv.x(),
                       uv.y());
  return Eigen::Vector2d(rect.f_px * dir.x() / dir.z() + rect.cx_px,
                         rect.f_px * dir.y() / dir.z() + rect.cy_px);
}

Result<Eigen::Vector3d> rectified_point(const RectifiedPair& pair, double u_left, double v,
                                        double d) {
  if (!(d > 0)) return Error::make(Errc::out_of_range, "rectify: disparity %.3f <= 0", d);
  const RectifiedCamera& l = pair.left;
  const double z = l.f_px * pair.baseline_mm / d;
  const Eigen::Vector3d pc((u_left - l.cx_px) * z / l.f_px, (v - l.cy_px) * z / l.f_px, z);
  return Eigen::Vector3d(l.R.transpose() * (pc - l.T_mm));
}

Result<RectifiedProjection> rectified_project(const RectifiedPair& pair,
                                              const Eigen::Vector3d& pw) {
  const RectifiedCamera& l = pair.left;
  const Eigen::Vector3d pc = l.R * pw + l.T_mm;
  if (!(pc.z() > 0)) return Error::make(Errc::out_of_range, "rectify: point behind the rig");
  RectifiedProjection out;
  out.uv_left = {l.f_px * pc.x() / pc.z() + l.cx_px, l.f_px * pc.y() / pc.z() + l.cy_px};
  out.disparity = l.f_px * pair.baseline_mm / pc.z();
  return out;
}

}  // namespace petra
