#include "hal/estop_monitor.hpp"

namespace petra::hal {

EstopState EstopMonitor::poll() {
  state_.line_fault = false;
  // Edges first: a press and release between two polls leaves only its edges.
  for (int i = 0; i < 64; ++i) {  // bounded: a chattering line cannot hold the cycle
    GpioEvent ev;
    auto got = line_.wait_event(ev, 0);
    if (!got) {
      error_ = got.error();
      state_.line_fault = true;
      break;
    }
    if (!*got) break;
    if (ev.edge == GpioEdge::rising) {
      ++state_.presses;
      state_.latched = true;
    }
  }
  auto level = line_.read();
  if (!level) {
    error_ = level.error();
    state_.line_fault = true;
  }
  state_.asserted = state_.line_fault || (level.ok() && *level);
  if (state_.asserted) state_.latched = true;
  return state_;
}

}  // namespace petra::hal
