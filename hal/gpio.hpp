// Digital lines behind two small interfaces: an output (camera trigger, arm
// power enable) and an input with edge events (e-stop). Values are logical:
// `true` means active, whatever the wiring (active-low lines are inverted by
// the backend). Backends: libgpiod on a real or simulated chip
// (hal/gpio_gpiod.hpp) and an in-process twin (hal/gpio_sim.hpp).
// No heap after a backend's open().
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "algo/core/result.hpp"

namespace petra::hal {

// Where a line is: a chip (name "gpiochip3", label "petra-io", path or number)
// and a line name from the device tree / gpio-sim configuration.
struct GpioLineConfig {
  static constexpr std::size_t kMaxName = 32;
  std::array<char, kMaxName> chip{};
  std::array<char, kMaxName> line{};
  bool active_low = false;
};

enum class GpioEdge : std::uint8_t { rising, falling };  // logical: rising = became active

struct GpioEvent {
  GpioEdge edge = GpioEdge::rising;
  std::int64_t time_ns = 0;  // CLOCK_MONOTONIC
};

class GpioOutput {
 public:
  virtual ~GpioOutput() = default;
  virtual Status set(bool active) = 0;
};

class GpioInput {
 public:
  virtual ~GpioInput() = default;
  // Current logical level.
  virtual Result<bool> read() = 0;
  // true with the oldest pending edge, false when none came within timeout_ms
  // (0 = poll); an error only when the line is broken.
  virtual Result<bool> wait_event(GpioEvent& out, int timeout_ms) = 0;
};

// Drives `line` active for width_us, then inactive again (the camera trigger).
// An error on the way down is reported as such: the line may be stuck active.
Status pulse(GpioOutput& line, std::uint32_t width_us);

}  // namespace petra::hal
