#include "hal/clock.hpp"

#include <ctime>

namespace petra::hal {

namespace {
std::int64_t read(clockid_t id) {
  timespec ts{};
  ::clock_gettime(id, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1000000000LL + ts.tv_nsec;
}
}  // namespace

std::int64_t SystemClock::monotonic_ns() const {
  return read(CLOCK_MONOTONIC);
}
std::int64_t SystemClock::realtime_ns() const {
  return read(CLOCK_REALTIME);
}

}  // namespace petra::hal
