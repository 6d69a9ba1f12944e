// In-process twin of the GPIO lines, for hosts without a gpio chip and for
// tests of the code that uses them. An output records its transitions; an
// input is driven by the test (drive()) and delivers edges to a waiting
// thread. Either can be "disconnected" to exercise the broken-line paths.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <mutex>

#include "hal/gpio.hpp"

namespace petra::hal {

class SimGpioOutput final : public GpioOutput {
 public:
  Status set(bool active) override;

  bool level() const;
  std::uint32_t rising_edges() const;
  std::uint32_t falling_edges() const;
  // Length of the last completed active period (ns), 0 when none yet.
  std::int64_t last_active_ns() const;
  void disconnect();

 private:
  mutable std::mutex mutex_;
  bool level_ = false;
  bool broken_ = false;
  std::uint32_t rising_ = 0;
  std::uint32_t falling_ = 0;
  std::int64_t rose_at_ns_ = 0;
  std::int64_t last_active_ns_ = 0;
};

class SimGpioInput final : public GpioInput {
 public:
  static constexpr std::uint32_t kQueueDepth = 16;  // edges kept for a slow reader

  Result<bool> read() override;
  Result<bool> wait_event(GpioEvent& out, int timeout_ms) override;

  // Sets the logical level as the outside world would; a change is an edge.
  void drive(bool active);
  void disconnect();
  std::uint32_t overflows() const;  // edges lost because the queue was full

 private:
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  bool level_ = false;
  bool broken_ = false;
  GpioEvent queue_[kQueueDepth];
  std::uint32_t head_ = 0;  // oldest pending
  std::uint32_t count_ = 0;
  std::uint32_t overflows_ = 0;
};

}  // namespace petra::hal
