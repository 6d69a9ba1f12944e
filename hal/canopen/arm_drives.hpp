// The arm's drive table: which CANopen node drives which joint and how joint
// angles map to encoder counts. One definition for the flight master
// (fsw/arm) and the simulated drives (sim/arm); docs/arm.md lists it.
//   joint k (1..5) -> node id k; 2^20 counts per turn; zero counts at 0 rad;
//   positive counts = positive joint angle. Ranges, profile velocity and
//   acceleration come from the arm's joint limits.
#pragma once

#include <array>
#include <cstdint>
#include <span>

#include "algo/core/result.hpp"
#include "hal/canopen/drive_link.hpp"

namespace petra::canopen {

inline constexpr std::size_t kArmJoints = 5;
inline constexpr std::uint8_t kArmFirstNodeId = 1;

struct ArmJointRanges {
  std::array<double, kArmJoints> min_rad{};
  std::array<double, kArmJoints> max_rad{};
  std::array<double, kArmJoints> max_velocity_rad_s{};
  std::array<double, kArmJoints> max_acceleration_rad_s2{};
};

// From any limits type with the same four per-joint arrays (arm::JointLimits).
template <class Limits>
ArmJointRanges joint_ranges_from(const Limits& l) {
  ArmJointRanges r;
  for (std::size_t j = 0; j < kArmJoints; ++j) {
    r.min_rad[j] = l.min_rad[j];
    r.max_rad[j] = l.max_rad[j];
    r.max_velocity_rad_s[j] = l.max_velocity_rad_s[j];
    r.max_acceleration_rad_s2[j] = l.max_acceleration_rad_s2[j];
  }
  return r;
}

// Drive configurations for the five joints; errors name the joint.
Result<std::array<DriveConfig, kArmJoints>> arm_drive_configs(const ArmJointRanges& ranges);

}  // namespace petra::canopen
