#include "hal/gpio_gpiod.hpp"

#include <cerrno>
#include <cstring>
#include <ctime>

#if PETRA_HAVE_LIBGPIOD
#include <gpiod.h>

#include "hal/errno_text.hpp"
#endif

namespace petra::hal {

namespace {

Status check_config(const GpioLineConfig& c) {
  if (c.chip[0] == '\0') return Error::make(Errc::missing_field, "gpio: chip is empty");
  if (c.line[0] == '\0')
    return Error::make(Errc::missing_field, "gpio %s: line name is empty", c.chip.data());
  return ok_status();
}

#if PETRA_HAVE_LIBGPIOD
// Opens the chip and finds the named line on it; errors name both.
Status find_line(const GpioLineConfig& c, gpiod_chip*& chip, gpiod_line*& line) {
  PETRA_TRY(check_config(c));
  chip = gpiod_chip_open_lookup(c.chip.data());
  if (chip == nullptr)
    return Error::make(Errc::io_error, "gpio chip '%s': %s", c.chip.data(), errno_text(errno));
  errno = 0;
  line = gpiod_chip_find_line(chip, c.line.data());
  if (line == nullptr) {
    const int err = errno;
    gpiod_chip_close(chip);
    chip = nullptr;
    return Error::make(Errc::io_error, "gpio chip '%s': no line named '%s'%s%s", c.chip.data(),
                       c.line.data(), err != 0 && err != ENOENT ? ": " : "",
                       err != 0 && err != ENOENT ? errno_text(err) : "");
  }
  return ok_status();
}

void release(gpiod_chip*& chip, gpiod_line*& line) {
  if (line != nullptr) gpiod_line_release(line);
  if (chip != nullptr) gpiod_chip_close(chip);
  line = nullptr;
  chip = nullptr;
}

int request_flags(const GpioLineConfig& c) {
  return c.active_low ? GPIOD_LINE_REQUEST_FLAG_ACTIVE_LOW : 0;
}
#endif

}  // namespace

#if PETRA_HAVE_LIBGPIOD

bool gpiod_available() {
  return true;
}

GpiodOutput::~GpiodOutput() {
  close();
}

Status GpiodOutput::open(const GpioLineConfig& config, const char* consumer, bool initial) {
  close();
  config_ = config;
  PETRA_TRY(find_line(config, chip_, line_));
  if (gpiod_line_request_output_flags(line_, consumer, request_flags(config), initial ? 1 : 0) <
      0) {
    const int err = errno;
    release(chip_, line_);
    return Error::make(Errc::io_error, "gpio %s/%s: cannot request as output: %s",
                       config.chip.data(), config.line.data(), errno_text(err));
  }
  return ok_status();
}

void GpiodOutput::close() {
  release(chip_, line_);
}

Status GpiodOutput::set(bool active) {
  if (line_ == nullptr) return Error::make(Errc::not_ready, "gpio output: not open");
  if (gpiod_line_set_value(line_, active ? 1 : 0) < 0)
    return Error::make(Errc::io_error, "gpio %s/%s: set %d: %s", config_.chip.data(),
                       config_.line.data(), active ? 1 : 0, errno_text(errno));
  return ok_status();
}

GpiodInput::~GpiodInput() {
  close();
}

Status GpiodInput::open(const GpioLineConfig& config, const char* consumer) {
  close();
  config_ = config;
  PETRA_TRY(find_line(config, chip_, line_));
  if (gpiod_line_request_both_edges_events_flags(line_, consumer, request_flags(config)) < 0) {
    const int err = errno;
    release(chip_, line_);
    return Error::make(Errc::io_error, "gpio %s/%s: cannot request edge events: %s",
                       config.chip.data(), config.line.data(), errno_text(err));
  }
  return ok_status();
}

void GpiodInput::close() {
  release(chip_, line_);
}

Result<bool> GpiodInput::read() {
  if (line_ == nullptr) return Error::make(Errc::not_ready, "gpio input: not open");
  const int v = gpiod_line_get_value(line_);
  if (v < 0)
    return Error::make(Errc::io_error, "gpio %s/%s: read: %s", config_.chip.data(),
                       config_.line.data(), errno_text(errno));
  return v != 0;
}

Result<bool> GpiodInput::wait_event(GpioEvent& out, int timeout_ms) {
  if (line_ == nullptr) return Error::make(Errc::not_ready, "gpio input: not open");
  if (timeout_ms < 0)
    return Error::make(Errc::invalid_argument, "gpio wait: timeout_ms %d < 0", timeout_ms);
  timespec t{};
  t.tv_sec = timeout_ms / 1000;
  t.tv_nsec = static_cast<long>(timeout_ms % 1000) * 1'000'000;
  const int r = gpiod_line_event_wait(line_, &t);
  if (r == 0) return false;
  gpiod_line_event ev{};
  if (r < 0 || gpiod_line_event_read(line_, &ev) < 0)
    return Error::make(Errc::io_error, "gpio %s/%s: event: %s", config_.chip.data(),
                       config_.line.data(), errno_text(errno));
  out.edge = ev.event_type == GPIOD_LINE_EVENT_RISING_EDGE ? GpioEdge::rising : GpioEdge::falling;
  out.time_ns = static_cast<std::int64_t>(ev.ts.tv_sec) * 1'000'000'000 + ev.ts.tv_nsec;
  return true;
}

#else  // built without libgpiod

bool gpiod_available() {
  return false;
}

namespace {
Error unavailable(const GpioLineConfig& c) {
  return Error::make(Errc::not_ready, "gpio %s/%s: built without libgpiod", c.chip.data(),
                     c.line.data());
}
}  // namespace

GpiodOutput::~GpiodOutput() = default;
Status GpiodOutput::open(const GpioLineConfig& config, const char*, bool) {
  PETRA_TRY(check_config(config));
  config_ = config;
  return unavailable(config);
}
void GpiodOutput::close() {}
Status GpiodOutput::set(bool) {
  return Error::make(Errc::not_ready, "gpio output: not open");
}

GpiodInput::~GpiodInput() = default;
Status GpiodInput::open(const GpioLineConfig& config, const char*) {
  PETRA_TRY(check_config(config));
  config_ = config;
  return unavailable(config);
}
void GpiodInput::close() {}
Result<bool> GpiodInput::read() {
  return Error::make(Errc::not_ready, "gpio input: not open");
}
Result<bool> GpiodInput::wait_event(GpioEvent&, int) {
  return Error::make(Errc::not_ready, "gpio input: not open");
}

#endif

}  // namespace petra::hal
