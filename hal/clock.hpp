// Time for the executive: a monotonic clock for the loop and deadlines, and
// wall time for telemetry time stamps. Tests inject a manual clock.
#pragma once

#include <cstdint>

namespace petra::hal {

inline constexpr std::int64_t kNsPerMs = 1000000;  // the clock's nanoseconds in a millisecond

class Clock {
 public:
  virtual ~Clock() = default;
  virtual std::int64_t monotonic_ns() const = 0;
  virtual std::int64_t realtime_ns() const = 0;
};

class SystemClock final : public Clock {
 public:
  std::int64_t monotonic_ns() const override;
  std::int64_t realtime_ns() const override;
};

}  // namespace petra::hal
