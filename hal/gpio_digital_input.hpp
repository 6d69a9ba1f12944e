// A GPIO input line (libgpiod or the twin) as the executive's DigitalInput
// (hal/digital_input.hpp), for the e-stop: read() is asserted while the line
// is active and also once after a press that was released between two reads
// (the edge latched by EstopMonitor), so a press shorter than a cycle still
// stops the arm. An unreadable line is an error (safety users treat it as
// asserted). No heap.
#pragma once

#include "hal/digital_input.hpp"
#include "hal/estop_monitor.hpp"

namespace petra::hal {

class GpioDigitalInput final : public DigitalInput {
 public:
  explicit GpioDigitalInput(GpioInput& line) : monitor_(line) {}
  Result<bool> read() override;
  const EstopState& state() const { return state_; }

 private:
  EstopMonitor monitor_;
  EstopState state_;
};

}  // namespace petra::hal
