#include "hal/gpio_digital_input.hpp"

namespace petra::hal {

Result<bool> GpioDigitalInput::read() {
  state_ = monitor_.poll();
  if (state_.line_fault) return monitor_.last_error();
  const bool asserted = state_.asserted || state_.latched;
  monitor_.clear_latch();  // a released press is reported once
  return asserted;
}

}  // namespace petra::hal
