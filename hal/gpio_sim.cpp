#include "hal/gpio_sim.hpp"

#include <chrono>
#include <ctime>

namespace petra::hal {

namespace {

std::int64_t now_ns() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

}  // namespace

Status SimGpioOutput::set(bool active) {
  std::lock_guard lock(mutex_);
  if (broken_) return Error::make(Errc::io_error, "sim gpio output: line disconnected");
  if (active && !level_) {
    ++rising_;
    rose_at_ns_ = now_ns();
  } else if (!active && level_) {
    ++falling_;
    last_active_ns_ = now_ns() - rose_at_ns_;
  }
  level_ = active;
  return ok_status();
}

bool SimGpioOutput::level() const {
  std::lock_guard lock(mutex_);
  return level_;
}
std::uint32_t SimGpioOutput::rising_edges() const {
  std::lock_guard lock(mutex_);
  return rising_;
}
std::uint32_t SimGpioOutput::falling_edges() const {
  std::lock_guard lock(mutex_);
  return falling_;
}
std::int64_t SimGpioOutput::last_active_ns() const {
  std::lock_guard lock(mutex_);
  return last_active_ns_;
}
void SimGpioOutput::disconnect() {
  std::lock_guard lock(mutex_);
  broken_ = true;
}

Result<bool> SimGpioInput::read() {
  std::lock_guard lock(mutex_);
  if (broken_) return Error::make(Errc::io_error, "sim gpio input: line disconnected");
  return level_;
}

Result<bool> SimGpioInput::wait_event(GpioEvent& out, int timeout_ms) {
  if (timeout_ms < 0)
    return Error::make(Errc::invalid_argument, "gpio wait: timeout_ms %d < 0", timeout_ms);
  std::unique_lock lock(mutex_);
  changed_.wait_for(lock, std::chrono::milliseconds(timeout_ms),
                    [this] { return count_ > 0 || broken_; });
  if (broken_) return Error::make(Errc::io_error, "sim gpio input: line disconnected");
  if (count_ == 0) return false;
  out = queue_[head_];
  head_ = (head_ + 1) % kQueueDepth;
  --count_;
  return true;
}

void SimGpioInput::drive(bool active) {
  {
    std::lock_guard lock(mutex_);
    if (active == level_) return;
    level_ = active;
    if (count_ == kQueueDepth) {
      ++overflows_;  // keep the oldest edges: they explain how we got here
    } else {
      queue_[(head_ + count_) % kQueueDepth] =
          GpioEvent{active ? GpioEdge::rising : GpioEdge::falling, now_ns()};
      ++count_;
    }
  }
  changed_.notify_all();
}

void SimGpioInput::disconnect() {
  {
    std::lock_guard lock(mutex_);
    broken_ = true;
  }
  changed_.notify_all();
}

std::uint32_t SimGpioInput::overflows() const {
  std::lock_guard lock(mutex_);
  return overflows_;
}

}  // namespace petra::hal
