#include "sim/scene/rig_builder.hpp"

#include <Eigen/Geometry>
#include <cmath>

namespace petra::sim {

namespace {

constexpr double kDeg = M_PI / 180.0;

// World -> camera rotation whose camera axes are x right, y down, z forward.
Eigen::Matrix3d rig_rotation(const RigPose& pose) {
  const double ch = std::cos(pose.heading_rad), sh = std::sin(pose.heading_rad);
  const double ct = std::cos(pose.tilt_rad), st = std::sin(pose.tilt_rad);
  const Eigen::Vector3d forward(-sh * ct, ch * ct, -st);
  const Eigen::Vector3d right(ch, sh, 0.0);
  const Eigen::Vector3d down = forward.cross(right);
  Eigen::Matrix3d r;
  r.row(0) = right.transpose();
  r.row(1) = down.transpose();
  r.row(2) = forward.transpose();
  // Roll about the optical axis (applied in the camera frame).
  return Eigen::Matrix3d(Eigen::AngleAxisd(pose.roll_rad, Eigen::Vector3d::UnitZ())) * r;
}

// A small rotation, up to `max_rad` about each axis.
Eigen::Matrix3d small_rotation(Rng& rng, double max_rad) {
  const double a = rng.uniform(-max_rad, max_rad);
  const double b = rng.uniform(-max_rad, max_rad);
  const double c = rng.uniform(-max_rad, max_rad);
  return Eigen::Matrix3d(Eigen::AngleAxisd(a, Eigen::Vector3d::UnitX()) *
                         Eigen::AngleAxisd(b, Eigen::Vector3d::UnitY()) *
                         Eigen::AngleAxisd(c, Eigen::Vector3d::UnitZ()));
}

}  // namespace

StereoRig build_rig(Rng& rng, const RigPose& pose) {
  const Eigen::Matrix3d r_rig = rig_rotation(pose);
  const Eigen::Vector3d right = r_rig.row(0).transpose();
  const Eigen::Vector3d down = r_rig.row(1).transpose();
  const Eigen::Vector3d forward = r_rig.row(2).transpose();
  const double baseline = 150.0 + rng.uniform(-0.5, 0.5);
  const double kappa_base = rng.uniform(0.0015, 0.0045);  // barrel, 1.4..4 % at the corners
  StereoRig rig;
  for (int k = 0; k < 2; ++k) {
    TsaiCamera& c = k == 0 ? rig.left : rig.right;
    c.width = 1024;
    c.height = 768;
    c.dx_mm = 0.00465;
    c.dy_mm = 0.00465;
    c.f_mm = 3.8 * (1.0 + rng.uniform(-0.01, 0.01));
    c.sx = 1.0 + rng.uniform(-0.002, 0.002);
    c.kappa1 = kappa_base * (1.0 + rng.uniform(-0.1, 0.1));
    c.cx_px = 511.5 + rng.uniform(-8, 8);
    c.cy_px = 383.5 + rng.uniform(-8, 8);
    c.R = small_rotation(rng, 0.4 * kDeg) * r_rig;
    // Mounting errors of up to half a millimetre off the nominal position.
    const double side = k == 0 ? -0.5 : 0.5;
    const Eigen::Vector3d centre = pose.midpoint_mm + side * baseline * right +
                                   rng.uniform(-0.5, 0.5) * down + rng.uniform(-0.5, 0.5) * forward;
    c.T_mm = -(c.R * centre);
  }
  return rig;
}

}  // namespace petra::sim
