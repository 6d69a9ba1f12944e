#include "fsw/event_log.hpp"

namespace petra::fsw {

tlm::TmTime tm_time(std::int64_t realtime_ns) {
  tlm::TmTime t;
  t.seconds = static_cast<std::uint32_t>(realtime_ns / 1000000000LL);
  t.micros = static_cast<std::uint32_t>((realtime_ns % 1000000000LL) / 1000);
  return t;
}

void EventLog::init(tlm::TlmQueue* queue, const hal::Clock* clock) {
  queue_ = queue;
  clock_ = clock;
}

void EventLog::record(std::uint16_t id, Severity severity,
                      const std::array<std::int32_t, 4>& args) {
  const std::int64_t now = clock_->realtime_ns();
  EventRecord& r = history_[next_];
  r = {id, severity, args, now};
  next_ = (next_ + 1) % kHistory;
  ++total_;
  tlm::Event e;
  e.event_id = id;
  e.severity = static_cast<std::uint8_t>(severity);
  e.args = args;
  queue_->push(e, tm_time(now));  // a full queue counts the drop
}

void EventLog::raise(EventId id, std::int32_t a0, std::int32_t a1, std::int32_t a2,
                     std::int32_t a3) {
  const EventDesc* d = find_event(static_cast<std::uint16_t>(id));
  record(static_cast<std::uint16_t>(id), d != nullptr ? d->severity : Severity::INFO,
         {a0, a1, a2, a3});
}

void EventLog::raise_rejection(Reason reason, std::uint8_t function_code, std::uint16_t detail,
                               std::uint32_t counter) {
  record(rejection_event(reason), Severity::WARNING,
         {function_code, detail, static_cast<std::int32_t>(counter), 0});
}

std::size_t EventLog::count(std::uint16_t id) const {
  std::size_t n = 0;
  const std::size_t valid = total_ < kHistory ? total_ : kHistory;
  for (std::size_t i = 0; i < valid; ++i)
    if (history_[i].id == id) ++n;
  return n;
}

const EventRecord* EventLog::latest() const {
  if (total_ == 0) return nullptr;
  return &history_[(next_ + kHistory - 1) % kHistory];
}

}  // namespace petra::fsw
