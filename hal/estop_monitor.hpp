// The e-stop as the executive sees it once per cycle: poll() never blocks,
// drains the line's edge events and reads its level. A press shorter than a
// cycle is still caught (its rising edge latches), and a line that cannot be
// read counts as pressed: the stop state is unknown, so the arm must stop.
// No heap.
#pragma once

#include <cstdint>

#include "hal/gpio.hpp"

namespace petra::hal {

struct EstopState {
  bool asserted = false;      // pressed now (or the line is unreadable)
  bool latched = false;       // pressed at any time since the last clear_latch()
  bool line_fault = false;    // the last poll could not read the line
  std::uint32_t presses = 0;  // rising edges seen since start
};

class EstopMonitor {
 public:
  explicit EstopMonitor(GpioInput& line) : line_(line) {}
  // One poll: drains pending edges, reads the level. The error, if any, is
  // kept in `last_error()` and reported as line_fault + asserted.
  EstopState poll();
  // The stop was acknowledged; the next poll latches again if it is still pressed.
  void clear_latch() { state_.latched = false; }
  const Error& last_error() const { return error_; }

 private:
  GpioInput& line_;
  EstopState state_;
  bool last_level_ = false;  // as of the last edge or read
  Error error_{};
};

}  // namespace petra::hal
