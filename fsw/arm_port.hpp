// ArmPort: what the executive needs from the arm (kinematics, CANopen drives:
// a later component). Motions are started by a command and polled each cycle.
// With no ArmPort configured, ARM_GOTO and ARM_STOW fail with ARM_UNAVAILABLE.
#pragma once

#include <array>
#include <cstdint>

#include "algo/core/result.hpp"

namespace petra::fsw {

enum class ArmProgress : std::uint8_t { IDLE, MOVING, REACHED, FAILED };

struct ArmTarget {
  std::array<double, 3> normal{};       // grind plane normal (out of the rock)
  std::array<double, 3> centroid_mm{};  // contact point
  double standoff_mm = 0;               // approach waypoint distance along the normal
};

class ArmPort {
 public:
  virtual ~ArmPort() = default;
  virtual Status start_goto(const ArmTarget& target) = 0;  // refuses unreachable poses
  virtual Status start_stow() = 0;
  virtual ArmProgress poll() = 0;  // called every cycle while moving
  virtual void quick_stop() = 0;   // ABORT, SAFE
};

}  // namespace petra::fsw
