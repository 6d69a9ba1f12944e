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
    // Kernels report the level found when the edge is handled, so a fast
    // press-release can arrive as two "falling" edges: a release while
    // already released means a press was missed in between.
    if (ev.edge == GpioEdge::rising || !last_level_) {
      ++state_.presses;
      state_.latched = true;
    }
    last_level_ = ev.edge == GpioEdge::rising;
  }
  auto level = line_.read();
  if (!level) {
    error_ = level.error();
    state_.line_fault = true;
  }
  state_.asserted = state_.line_fault || (level.ok() && *level);
  if (level.ok()) last_level_ = *level;
  if (state_.asserted) state_.latched = true;
  return state_;
}

}  // namespace petra::hal
