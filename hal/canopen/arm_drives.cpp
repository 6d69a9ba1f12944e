#include "hal/canopen/arm_drives.hpp"

namespace petra::canopen {

Result<std::array<DriveConfig, kArmJoints>> arm_drive_configs(const ArmJointRanges& r) {
  std::array<DriveConfig, kArmJoints> out{};
  for (std::size_t j = 0; j < kArmJoints; ++j) {
    DriveConfig& c = out[j];
    c.node_id = static_cast<std::uint8_t>(kArmFirstNodeId + j);
    c.min_position_rad = r.min_rad[j];
    c.max_position_rad = r.max_rad[j];
    c.profile_velocity_rad_s = r.max_velocity_rad_s[j];
    c.profile_acceleration_rad_s2 = r.max_acceleration_rad_s2[j];
    // Quick stop brakes three times harder than a planned stop.
    c.quick_stop_deceleration_rad_s2 = 3.0 * r.max_acceleration_rad_s2[j];
    auto ok = validate_drive_config(c);
    if (!ok) return Error::make(ok.code(), "joint %zu: %s", j + 1, ok.error().message);
  }
  return out;
}

}  // namespace petra::canopen
