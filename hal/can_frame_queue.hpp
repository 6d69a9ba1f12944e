// A fixed-capacity FIFO of CAN frames (ring buffer): the backends' send and
// receive queues. push() on a full queue fails and changes nothing.
#pragma once

#include <array>
#include <cstddef>

#include "hal/can.hpp"

namespace petra::hal {

template <std::size_t N>
class CanFrameQueue {
 public:
  static_assert(N > 0);
  [[nodiscard]] bool push(const CanFrame& frame) {
    if (size_ == N) return false;
    items_[(head_ + size_) % N] = frame;
    ++size_;
    return true;
  }
  [[nodiscard]] bool pop(CanFrame& out) {
    if (size_ == 0) return false;
    out = items_[head_];
    head_ = (head_ + 1) % N;
    --size_;
    return true;
  }
  const CanFrame& front() const { return items_[head_]; }
  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  bool full() const { return size_ == N; }
  void clear() { head_ = size_ = 0; }
  static constexpr std::size_t capacity() { return N; }

 private:
  std::array<CanFrame, N> items_{};
  std::size_t head_ = 0;
  std::size_t size_ = 0;
};

}  // namespace petra::hal
