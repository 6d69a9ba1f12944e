#include "hal/canopen/cia402.hpp"

namespace petra::canopen {

const char* drive_state_name(DriveState state) {
  switch (state) {
    case DriveState::not_ready_to_switch_on:
      return "not_ready_to_switch_on";
    case DriveState::switch_on_disabled:
      return "switch_on_disabled";
    case DriveState::ready_to_switch_on:
      return "ready_to_switch_on";
    case DriveState::switched_on:
      return "switched_on";
    case DriveState::operation_enabled:
      return "operation_enabled";
    case DriveState::quick_stop_active:
      return "quick_stop_active";
    case DriveState::fault_reaction_active:
      return "fault_reaction_active";
    case DriveState::fault:
      return "fault";
    case DriveState::unknown:
      return "unknown";
  }
  return "unknown";
}

DriveState decode_statusword(std::uint16_t sw) {
  // Bits: 0 ready to switch on, 1 switched on, 2 operation enabled, 3 fault,
  // 5 quick stop (active low), 6 switch on disabled.
  if ((sw & 0x004F) == 0x0000) return DriveState::not_ready_to_switch_on;
  if ((sw & 0x004F) == 0x0040) return DriveState::switch_on_disabled;
  if ((sw & 0x006F) == 0x0021) return DriveState::ready_to_switch_on;
  if ((sw & 0x006F) == 0x0023) return DriveState::switched_on;
  if ((sw & 0x006F) == 0x0027) return DriveState::operation_enabled;
  if ((sw & 0x006F) == 0x0007) return DriveState::quick_stop_active;
  if ((sw & 0x004F) == 0x000F) return DriveState::fault_reaction_active;
  if ((sw & 0x004F) == 0x0008) return DriveState::fault;
  return DriveState::unknown;
}

std::uint16_t statusword_bits(DriveState state) {
  switch (state) {
    case DriveState::not_ready_to_switch_on:
      return 0x0000;
    case DriveState::switch_on_disabled:
      return 0x0040;
    case DriveState::ready_to_switch_on:
      return 0x0021;
    case DriveState::switched_on:
      return 0x0023;
    case DriveState::operation_enabled:
      return 0x0027;
    case DriveState::quick_stop_active:
      return 0x0007;
    case DriveState::fault_reaction_active:
      return 0x000F;
    case DriveState::fault:
      return 0x0008;
    case DriveState::unknown:
      return 0x0000;
  }
  return 0x0000;
}

DriveCommand decode_controlword(std::uint16_t cw) {
  if (cw & 0x0080) return DriveCommand::fault_reset;
  if ((cw & 0x0002) == 0) return DriveCommand::disable_voltage;  // x x 0 x
  if ((cw & 0x0006) == 0x0002) return DriveCommand::quick_stop;  // x 0 1 x
  if ((cw & 0x0007) == 0x0006) return DriveCommand::shutdown;    // x 1 1 0
  if ((cw & 0x000F) == 0x0007) return DriveCommand::switch_on;   // 0 1 1 1 (= disable operation)
  if ((cw & 0x000F) == 0x000F) return DriveCommand::enable_operation;
  return DriveCommand::none;
}

DriveState next_drive_state(DriveState s, DriveCommand c, int quick_stop_option_code) {
  using S = DriveState;
  using C = DriveCommand;
  switch (s) {
    case S::switch_on_disabled:
      return c == C::shutdown ? S::ready_to_switch_on : s;
    case S::ready_to_switch_on:
      if (c == C::switch_on) return S::switched_on;
      if (c == C::enable_operation) return S::operation_enabled;  // transitions 3 + 4 at once
      if (c == C::disable_voltage || c == C::quick_stop) return S::switch_on_disabled;
      return s;
    case S::switched_on:
      if (c == C::enable_operation) return S::operation_enabled;
      if (c == C::shutdown) return S::ready_to_switch_on;
      if (c == C::disable_voltage || c == C::quick_stop) return S::switch_on_disabled;
      return s;
    case S::operation_enabled:
      if (c == C::switch_on) return S::switched_on;  // disable operation
      if (c == C::shutdown) return S::ready_to_switch_on;
      if (c == C::disable_voltage) return S::switch_on_disabled;
      if (c == C::quick_stop) return S::quick_stop_active;
      return s;
    case S::quick_stop_active:
      if (c == C::disable_voltage) return S::switch_on_disabled;
      // Options 5..8 hold in quick stop; enable operation resumes (transition 16).
      if (quick_stop_option_code >= 5 && quick_stop_option_code <= 8) {
        return c == C::enable_operation ? S::operation_enabled : s;
      }
      return s;
    case S::fault:
      return c == C::fault_reset ? S::switch_on_disabled : s;
    case S::not_ready_to_switch_on:
    case S::fault_reaction_active:
    case S::unknown:
      return s;
  }
  return s;
}

}  // namespace petra::canopen
