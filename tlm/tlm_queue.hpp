// The downlink queue: a ring of fixed-size packet slots over memory given at
// init. Pushing takes the APID's next sequence count, encodes the packet in
// place and never blocks: when every slot is taken the packet is dropped and
// counted (housekeeping reports the drops). A dropped packet has used its
// count, so the ground sees the loss as a gap on that APID. Single-threaded.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "tlm/telemetry.hpp"

namespace petra::tlm {

class TlmQueue {
 public:
  static constexpr std::size_t kSlotBytes = kMaxTmBytes;
  static constexpr std::size_t bytes_for(std::size_t slots) { return slots * kSlotBytes; }

  // storage: bytes_for(n) bytes; lengths: n entries. Both outlive the queue.
  void init(std::span<std::uint8_t> storage, std::span<std::uint16_t> lengths);

  // Encodes `packet` at the tail. False (and one more drop, its sequence count
  // spent) when full.
  template <class T>
  bool push(const T& packet, TmTime time, wire::SeqFlags flags = wire::SeqFlags::unsegmented) {
    const std::uint16_t seq = next_seq(static_cast<std::uint16_t>(ApidOf<T>::value));
    if (full()) {
      ++dropped_;
      return false;
    }
    const std::size_t n = encode_tm(packet, seq, flags, time, slot(tail_));
    commit(n);
    return true;
  }

  bool empty() const { return count_ == 0; }
  bool full() const { return count_ == capacity_; }
  std::size_t size() const { return count_; }
  std::size_t capacity() const { return capacity_; }
  std::size_t free_slots() const { return capacity_ - count_; }
  std::size_t high_water() const { return high_water_; }
  std::uint32_t dropped() const { return dropped_; }
  void reset_counters() { dropped_ = 0; }

  // Oldest packet; valid until pop().
  std::span<const std::uint8_t> front() const;
  void pop();

 private:
  std::span<std::uint8_t> slot(std::size_t i) {
    return storage_.subspan(i * kSlotBytes, kSlotBytes);
  }
  std::uint16_t next_seq(std::uint16_t apid);
  void commit(std::size_t bytes);

  std::span<std::uint8_t> storage_;
  std::span<std::uint16_t> lengths_;
  std::size_t capacity_ = 0;
  std::size_t head_ = 0;
  std::size_t tail_ = 0;
  std::size_t count_ = 0;
  std::size_t high_water_ = 0;
  std::uint32_t dropped_ = 0;
  std::array<std::uint16_t, wire::kMaxApid + 1> seq_{};
};

}  // namespace petra::tlm
