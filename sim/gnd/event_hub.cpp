#include "sim/gnd/event_hub.hpp"

#include <chrono>

namespace petra::gnd {

void EventHub::publish(std::string event, std::string json) {
  {
    std::lock_guard lock(mutex_);
    kept_.push_back({next_seq_++, std::move(event), std::move(json)});
    while (kept_.size() > capacity_) kept_.pop_front();
  }
  changed_.notify_all();
}

std::vector<EventHub::Message> EventHub::wait_after(std::uint64_t after, int timeout_ms) {
  std::unique_lock lock(mutex_);
  changed_.wait_for(lock, std::chrono::milliseconds(timeout_ms),
                    [&] { return closed_ || next_seq_ - 1 > after; });
  std::vector<Message> out;
  for (const Message& m : kept_)
    if (m.seq > after) out.push_back(m);
  return out;
}

void EventHub::close() {
  {
    std::lock_guard lock(mutex_);
    closed_ = true;
  }
  changed_.notify_all();
}

bool EventHub::closed() const {
  std::lock_guard lock(mutex_);
  return closed_;
}

}  // namespace petra::gnd
