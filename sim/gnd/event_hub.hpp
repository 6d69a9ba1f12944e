// Fan-out of ground-station messages to every connected page (server-sent
// events). Messages are numbered; the last `capacity` are kept so a page that
// connects (or reconnects) late still sees the recent acknowledgements,
// events, planes and housekeeping. Thread-safe: the telemetry thread
// publishes, one HTTP thread per page reads.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <mutex>
#include <string>
#include <vector>

namespace petra::gnd {

class EventHub {
 public:
  explicit EventHub(std::size_t capacity = 4000) : capacity_(capacity) {}

  // `event` is the SSE event name, `json` its data (one line).
  void publish(std::string event, std::string json);

  struct Message {
    std::uint64_t seq = 0;
    std::string event;
    std::string json;
  };
  // Messages numbered above `after` (oldest first), waiting up to timeout_ms
  // for one to arrive. Returns at once when closed.
  std::vector<Message> wait_after(std::uint64_t after, int timeout_ms);

  // Wakes every waiting reader and makes later waits return at once.
  void close();
  bool closed() const;

 private:
  std::size_t capacity_;
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<Message> kept_;
  std::uint64_t next_seq_ = 1;
  bool closed_ = false;
};

}  // namespace petra::gnd
