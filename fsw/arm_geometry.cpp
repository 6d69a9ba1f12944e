#include "fsw/arm_geometry.hpp"

#include <numbers>

namespace petra::fsw {

::petra::arm::ArmGeometry arm_geometry(const FswConfig& config) {
  ::petra::arm::ArmGeometry g = ::petra::arm::rover_arm_geometry();
  if (config.arm.has_mount) {
    const auto& m = config.arm.mount;
    g.world_from_base =
        Eigen::Translation3d(m[0], m[1], m[2]) *
        Eigen::AngleAxisd(m[3] * std::numbers::pi / 180.0, Eigen::Vector3d::UnitZ());
  }
  return g;
}

}  // namespace petra::fsw
