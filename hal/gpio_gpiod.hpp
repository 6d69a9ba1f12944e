// GPIO lines through libgpiod 1.6 (Debian 12's libgpiod-dev): a real chip on
// the rover, gpio-sim in the HIL bench. Lines are found by chip (name, label,
// path or number, as gpiod_chip_open_lookup takes it) and line name; active-low
// wiring is applied by the kernel, so values are logical. Requests are made in
// open(); set/read/wait are single ioctls or polls and allocate nothing.
// Built without libgpiod (the aarch64 cross build has no arm64 libgpiod-dev):
// gpiod_available() is false and open() fails with Errc::not_ready.
#pragma once

#include "hal/gpio.hpp"

struct gpiod_chip;
struct gpiod_line;

namespace petra::hal {

bool gpiod_available();

class GpiodOutput final : public GpioOutput {
 public:
  GpiodOutput() = default;
  GpiodOutput(const GpiodOutput&) = delete;
  GpiodOutput& operator=(const GpiodOutput&) = delete;
  ~GpiodOutput() override;

  // Requests the line as an output, driven to `initial` (logical) at once.
  Status open(const GpioLineConfig& config, const char* consumer, bool initial);
  void close();
  Status set(bool active) override;

 private:
  gpiod_chip* chip_ = nullptr;
  gpiod_line* line_ = nullptr;
  GpioLineConfig config_{};
};

class GpiodInput final : public GpioInput {
 public:
  GpiodInput() = default;
  GpiodInput(const GpiodInput&) = delete;
  GpiodInput& operator=(const GpiodInput&) = delete;
  ~GpiodInput() override;

  // Requests the line as an input with both-edge events.
  Status open(const GpioLineConfig& config, const char* consumer);
  void close();
  Result<bool> read() override;
  Result<bool> wait_event(GpioEvent& out, int timeout_ms) override;

 private:
  gpiod_chip* chip_ = nullptr;
  gpiod_line* line_ = nullptr;
  GpioLineConfig config_{};
};

}  // namespace petra::hal
