// ArmPort: what the executive needs from the arm (implemented by fsw/arm/
// FlightArm: kinematics, planning and the CANopen drives, docs/arm.md).
// Motions are started by a command; poll() runs every cycle, moving or not
// (it keeps the drives' bus alive: heartbeats, SYNC, feedback).
// With no ArmPort configured, ARM_GOTO and ARM_STOW fail with ARM_UNAVAILABLE.
#pragma once

#include <array>
#include <cstdint>

#include "algo/core/result.hpp"
#include "tlm/event_defs.hpp"
#include "tlm/telemetry.hpp"

namespace petra::fsw {

enum class ArmProgress : std::uint8_t { IDLE, MOVING, REACHED, FAILED };

struct ArmTarget {
  std::array<double, 3> normal{};       // grind plane normal (out of the rock)
  std::array<double, 3> centroid_mm{};  // contact point
  double standoff_mm = 0;               // approach waypoint distance along the normal
};

// An event for the executive's log; `safe` asks for SAFE (drive fault, lost heartbeat).
struct ArmEventOut {
  EventId id = EventId::ARM_READY;
  std::array<std::int32_t, 4> args{};
  bool safe = false;
};

class ArmPort {
 public:
  virtual ~ArmPort() = default;
  // Refusals: Errc::not_ready when the drives cannot move now (ARM_NOT_READY),
  // any other code when the target is out of reach or limits (ARM_REFUSED).
  virtual Status start_goto(const ArmTarget& target) = 0;
  virtual Status start_stow() = 0;
  virtual ArmProgress poll() = 0;  // every cycle
  virtual void quick_stop() = 0;   // ABORT, e-stop, SAFE
  // Leaving SAFE: recover from a drive fault (reboot the drives); nothing otherwise.
  virtual Status reset() { return {}; }
  // Drained every cycle after poll().
  virtual bool pop_event(ArmEventOut& out) {
    (void)out;
    return false;
  }
  // ARM_STATUS telemetry (sent with housekeeping); false: nothing to report.
  virtual bool status(tlm::ArmStatus& out) const {
    (void)out;
    return false;
  }
};

}  // namespace petra::fsw
