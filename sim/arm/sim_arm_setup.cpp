#include "sim/arm/sim_arm_setup.hpp"

#include "algo/arm/kinematics.hpp"
#include "algo/core/assert.hpp"

namespace petra::sim {

ArmDriveConfigs default_arm_drive_configs() {
  auto configs =
      canopen::arm_drive_configs(canopen::joint_ranges_from(arm::default_joint_limits()));
  PETRA_ASSERT(configs.ok());  // the defaults are a programming constant
  return *configs;
}

ArmSimParams sim_params_at(const ArmDriveConfigs& configs,
                           std::span<const double, canopen::kArmJoints> pose) {
  ArmSimParams p{};
  for (std::size_t j = 0; j < canopen::kArmJoints; ++j) {
    p[j].node_id = configs[j].node_id;
    p[j].initial_position_counts = canopen::position_to_counts(configs[j], pose[j]);
  }
  return p;
}

}  // namespace petra::sim
