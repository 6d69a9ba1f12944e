#include "hal/gpio.hpp"

#include <cerrno>
#include <ctime>

namespace petra::hal {

Status pulse(GpioOutput& line, std::uint32_t width_us) {
  if (width_us == 0 || width_us > 1'000'000)
    return Error::make(Errc::invalid_argument, "pulse: width %u us outside 1..1000000", width_us);
  PETRA_TRY(line.set(true));
  timespec t{};
  t.tv_sec = static_cast<time_t>(width_us / 1'000'000);
  t.tv_nsec = static_cast<long>(width_us % 1'000'000) * 1000;
  while (clock_nanosleep(CLOCK_MONOTONIC, 0, &t, &t) == EINTR) {
  }
  if (auto s = line.set(false); !s)
    return Error::make(s.error().code, "pulse: line may be stuck active: %s", s.error().message);
  return ok_status();
}

}  // namespace petra::hal
