#include "tlm/tlm_queue.hpp"

#include "algo/core/assert.hpp"

namespace petra::tlm {

void TlmQueue::init(std::span<std::uint8_t> storage, std::span<std::uint16_t> lengths) {
  PETRA_ASSERT(storage.size() >= bytes_for(lengths.size()));
  storage_ = storage;
  lengths_ = lengths;
  capacity_ = lengths.size();
  head_ = tail_ = count_ = high_water_ = 0;
  dropped_ = 0;
}

std::uint16_t TlmQueue::next_seq(std::uint16_t apid) {
  const std::uint16_t s = seq_[apid & wire::kMaxApid];
  seq_[apid & wire::kMaxApid] = static_cast<std::uint16_t>((s + 1) & wire::kSeqCountMask);
  return s;
}

void TlmQueue::commit(std::size_t bytes) {
  PETRA_ASSERT(bytes > 0 && bytes <= kSlotBytes);
  lengths_[tail_] = static_cast<std::uint16_t>(bytes);
  tail_ = (tail_ + 1) % capacity_;
  ++count_;
  if (count_ > high_water_) high_water_ = count_;
}

std::span<const std::uint8_t> TlmQueue::front() const {
  PETRA_ASSERT(count_ > 0);
  return storage_.subspan(head_ * kSlotBytes, lengths_[head_]);
}

void TlmQueue::pop() {
  PETRA_ASSERT(count_ > 0);
  head_ = (head_ + 1) % capacity_;
  --count_;
}

}  // namespace petra::tlm
