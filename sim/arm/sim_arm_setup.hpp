// Simulated drives matching the arm's drive table (hal/canopen/arm_drives.hpp),
// standing at a given pose: what `petra sim-arm` and the tests power up.
#pragma once

#include <array>
#include <span>

#include "algo/core/result.hpp"
#include "hal/canopen/arm_drives.hpp"
#include "sim/arm/sim_drive.hpp"

namespace petra::sim {

using ArmDriveConfigs = std::array<canopen::DriveConfig, canopen::kArmJoints>;
using ArmSimParams = std::array<SimDriveParams, canopen::kArmJoints>;

// The drive table for the default joint limits (arm::default_joint_limits()).
ArmDriveConfigs default_arm_drive_configs();

// Each drive's node id from `configs`, its encoder at `pose_rad`.
ArmSimParams sim_params_at(const ArmDriveConfigs& configs,
                           std::span<const double, canopen::kArmJoints> pose_rad);

}  // namespace petra::sim
