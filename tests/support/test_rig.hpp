// A Bumblebee2-like stereo rig for tests (150 mm baseline, 1024x768, small
// misalignments and radial distortion, looking down at the ground ahead).
// Header-only; tests may allocate.
#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <random>

#include "algo/camera/camera_model.hpp"

namespace petra::test {

// 1024x768 Bumblebee2-like optics, seeded scatter of focal length, aspect,
// principal point and radial distortion around their nominal values.
inline void set_bumblebee_optics(TsaiCamera& c, std::mt19937_64& rng, double kappa1) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  c.width = 1024;
  c.height = 768;
  c.f_mm = 3.8 + 0.02 * u(rng);
  c.dx_mm = c.dy_mm = 0.00465;
  c.sx = 1.0 + 0.002 * u(rng);
  c.cx_px = 512 + 5 * u(rng);
  c.cy_px = 384 + 5 * u(rng);
  c.kappa1 = kappa1 + 0.001 * u(rng);
}

inline StereoRig bumblebee_rig(std::uint64_t seed, double kappa1 = -0.003) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  StereoRig rig;
  for (int k = 0; k < 2; ++k) {
    TsaiCamera& c = k == 0 ? rig.left : rig.right;
    set_bumblebee_optics(c, rng, kappa1);
    c.R = Eigen::Matrix3d(Eigen::AngleAxisd(0.5 + 0.01 * u(rng), Eigen::Vector3d::UnitX()) *
                          Eigen::AngleAxisd(0.01 * u(rng), Eigen::Vector3d::UnitY()) *
                          Eigen::AngleAxisd(0.01 * u(rng), Eigen::Vector3d::UnitZ()));
    const Eigen::Vector3d centre(k == 0 ? 0.0 : 150.0 + u(rng), 2 * u(rng), 2 * u(rng));
    c.T_mm = -(c.R * centre);
  }
  return rig;
}

}  // namespace petra::test

namespace petra::test {

// A rig in a world with z up and the ground at z = 0: the left camera at
// `eye` looks at `target`, the right one 150 mm to its right; Bumblebee2-like
// optics with distortion and small misalignments (seeded).
inline StereoRig looking_rig(std::uint64_t seed, const Eigen::Vector3d& eye = {0, -600, 500},
                             const Eigen::Vector3d& target = {0, 0, 20}) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Eigen::Vector3d z = (target - eye).normalized();
  const Eigen::Vector3d x = z.cross(Eigen::Vector3d::UnitZ()).normalized();
  const Eigen::Vector3d y = z.cross(x);
  Eigen::Matrix3d base;
  base.row(0) = x.transpose();
  base.row(1) = y.transpose();
  base.row(2) = z.transpose();
  StereoRig rig;
  for (int k = 0; k < 2; ++k) {
    TsaiCamera& c = k == 0 ? rig.left : rig.right;
    set_bumblebee_optics(c, rng, -0.003);
    c.R = Eigen::Matrix3d(Eigen::AngleAxisd(0.005 * u(rng), Eigen::Vector3d::UnitX()) *
                          Eigen::AngleAxisd(0.005 * u(rng), Eigen::Vector3d::UnitY()) *
                          Eigen::AngleAxisd(0.005 * u(rng), Eigen::Vector3d::UnitZ())) *
          base;
    const Eigen::Vector3d centre = eye + (k == 0 ? 0.0 : 150.0) * x;
    c.T_mm = -(c.R * centre);
  }
  return rig;
}

}  // namespace petra::test
