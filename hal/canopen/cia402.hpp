// CiA 402 (drives and motion control) subset: the power state machine read
// from the statusword and driven by controlword commands, and the profile
// position mode handshake. Pure functions; no OS calls, no heap.
#pragma once

#include <cstdint>

namespace petra::canopen {

// Power states (CiA 402 figure "state machine"), decoded from the statusword.
enum class DriveState : std::uint8_t {
  not_ready_to_switch_on = 0,
  switch_on_disabled = 1,
  ready_to_switch_on = 2,
  switched_on = 3,
  operation_enabled = 4,
  quick_stop_active = 5,
  fault_reaction_active = 6,
  fault = 7,
  unknown = 8,
};
const char* drive_state_name(DriveState state);

// Statusword bits 0-3, 5, 6 select the state (the masks of CiA 402 table 30).
DriveState decode_statusword(std::uint16_t statusword);

// The statusword bits a drive reports for a state (bits 0-3, 5, 6; others 0).
std::uint16_t statusword_bits(DriveState state);

namespace statusword {
inline constexpr std::uint16_t kVoltageEnabled = 1u << 4;
inline constexpr std::uint16_t kWarning = 1u << 7;
inline constexpr std::uint16_t kRemote = 1u << 9;
inline constexpr std::uint16_t kTargetReached = 1u << 10;
inline constexpr std::uint16_t kInternalLimit = 1u << 11;
inline constexpr std::uint16_t kSetPointAcknowledge = 1u << 12;  // profile position mode
inline constexpr std::uint16_t kFollowingError = 1u << 13;       // profile position mode
}  // namespace statusword

// Controlword commands (bits 0-3 and 7) and profile position bits 4-8.
namespace controlword {
inline constexpr std::uint16_t kDisableVoltage = 0x0000;
inline constexpr std::uint16_t kQuickStop = 0x0002;
inline constexpr std::uint16_t kShutdown = 0x0006;
inline constexpr std::uint16_t kSwitchOn = 0x0007;  // also "disable operation"
inline constexpr std::uint16_t kEnableOperation = 0x000F;
inline constexpr std::uint16_t kFaultReset = 0x0080;  // acts on the rising edge
inline constexpr std::uint16_t kNewSetPoint = 1u << 4;
inline constexpr std::uint16_t kChangeSetImmediately = 1u << 5;
inline constexpr std::uint16_t kRelative = 1u << 6;
inline constexpr std::uint16_t kHalt = 1u << 8;
inline constexpr std::uint16_t kCommandMask = 0x008F;
}  // namespace controlword

enum class DriveCommand : std::uint8_t {
  none = 0,
  shutdown,
  switch_on,
  disable_voltage,
  quick_stop,
  disable_operation,
  enable_operation,
  fault_reset,
};
// Reads the command in a controlword (bits 0-3, 7; CiA 402 table 28).
// fault_reset is reported whenever bit 7 is set; the drive acts on its edge.
DriveCommand decode_controlword(std::uint16_t controlword);

// The state a drive moves to on `command` from `state` (the drive side of the
// state machine; the simulated drive uses it). Unchanged when not allowed.
// quick_stop_option_code 5..8 keeps the drive in quick_stop_active (holding);
// others end in switch_on_disabled.
DriveState next_drive_state(DriveState state, DriveCommand command, int quick_stop_option_code);

inline constexpr std::int8_t kModeProfilePosition = 1;

}  // namespace petra::canopen
