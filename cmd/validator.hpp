// Telecommand validation: one total function from raw datagram bytes to a
// verdict, run before anything is dispatched (cFS style). Checks, in order:
// size, primary header, length field, CRC, HMAC, counter, function code,
// argument length, argument ranges, argument consistency, mode. The first
// failing check is the reason; nothing is changed by this function.
#pragma once

#include <cstdint>
#include <span>

#include "algo/wire/reasons.hpp"
#include "cmd/auth.hpp"
#include "cmd/commands.hpp"
#include "cmd/mode.hpp"

namespace petra::cmd {

struct ValidationContext {
  const AuthKey* key = nullptr;
  std::uint32_t last_counter = 0;  // last accepted counter; a command needs a larger one
  Mode mode = Mode::IDLE;
  int image_width = 0;  // the camera's frame size, for ROI checks
  int image_height = 0;
  // The memory budget fixed at boot (0: no limit) and the envelope in force.
  int max_roi_width = 0;  // px, original left image
  int max_roi_height = 0;
  int max_disparities = 0;
  int disp_min_px = 0;
  int disp_max_px = 0;
};

struct Verdict {
  Reason reason = Reason::NONE;  // NONE: valid, `command` is set
  std::uint16_t detail = 0;      // field index, mode, or parameter id (see reasons.hpp)
  std::uint8_t function_code = 0;
  // True once the HMAC verified and the counter was fresh: the executive then
  // records the counter even when a later check rejects the command, so an
  // authentic command can never be replayed in another mode.
  bool authenticated = false;
  Command command;  // counter set once the HMAC verified (also for REPLAY)

  bool ok() const { return reason == Reason::NONE; }
};

Verdict validate_command(std::span<const std::uint8_t> datagram, const ValidationContext& ctx);

// SELECT_ROI's argument checks (ranges, ROI inside the image, click inside
// the ROI, the memory budget), also applied on board to a selection not sent
// by the ground (SELECT_PROPOSAL). reason NONE: fine.
struct SelectionRefusal {
  Reason reason = Reason::NONE;
  std::uint16_t detail = 0;  // field index, or the budget's limit (as the Verdict's)
};
SelectionRefusal selection_refusal(const SelectRoiArgs& roi, const ValidationContext& ctx);

}  // namespace petra::cmd
