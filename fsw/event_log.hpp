// EventLog: raises events (id, severity, four arguments, time) as EVENT
// telemetry and keeps the last kHistory of them for inspection. Event ids and
// texts: tlm/event_defs.hpp. Owns no memory beyond its fixed history.
#pragma once

#include <array>
#include <cstdint>

#include "hal/clock.hpp"
#include "tlm/event_defs.hpp"
#include "tlm/tlm_queue.hpp"

namespace petra::fsw {

struct EventRecord {
  std::uint16_t id = 0;
  Severity severity = Severity::INFO;
  std::array<std::int32_t, 4> args{};
  std::int64_t time_ns = 0;
};

class EventLog {
 public:
  static constexpr std::size_t kHistory = 64;

  void init(tlm::TlmQueue* queue, const hal::Clock* clock);

  void raise(EventId id, std::int32_t a0 = 0, std::int32_t a1 = 0, std::int32_t a2 = 0,
             std::int32_t a3 = 0);
  // The rejection event of `reason` (its own id, tlm/event_defs.hpp).
  void raise_rejection(Reason reason, std::uint8_t function_code, std::uint16_t detail,
                       std::uint32_t counter);

  std::uint32_t total() const { return total_; }
  // Events still in the history with this id.
  std::size_t count(std::uint16_t id) const;
  const EventRecord* latest() const;

 private:
  void record(std::uint16_t id, Severity severity, const std::array<std::int32_t, 4>& args);

  tlm::TlmQueue* queue_ = nullptr;
  const hal::Clock* clock_ = nullptr;
  std::array<EventRecord, kHistory> history_{};
  std::size_t next_ = 0;
  std::uint32_t total_ = 0;
};

// Telemetry time stamp of a CLOCK_REALTIME instant.
tlm::TmTime tm_time(std::int64_t realtime_ns);

}  // namespace petra::fsw
