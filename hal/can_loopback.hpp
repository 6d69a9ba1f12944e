// An in-process CAN bus: endpoints attach to one bus object and every frame one
// endpoint sends reaches every other endpoint whose filters accept it (CAN is a
// broadcast bus; like SocketCAN, a sender does not receive its own frames).
// For tests, ground simulation and hosts without CAN. Thread-safe: the master
// and simulated drives may run on different threads; receive() with a timeout
// waits on a condition variable.
// Fault injection: an endpoint can be put bus-off (its sends are refused and
// counted, as a real controller would) and error frames can be injected.
// Memory: all queues live inside the bus object (kMaxEndpoints x kQueueDepth
// frames, about 36 kB); attach() takes a slot from a fixed table. No heap.
#pragma once

#include <array>
#include <condition_variable>
#include <cstddef>
#include <mutex>
#include <span>

#include "hal/can.hpp"
#include "hal/can_frame_queue.hpp"

namespace petra::hal {

class CanLoopbackBus {
 public:
  static constexpr std::size_t kMaxEndpoints = 12;
  static constexpr std::size_t kQueueDepth = 192;

  class Endpoint final : public CanPort {
   public:
    Status send(const CanFrame& frame) override;
    Result<bool> receive(CanFrame& out, int timeout_ms) override;
    CanHealth health() const override;

   private:
    friend class CanLoopbackBus;
    CanLoopbackBus* bus_ = nullptr;
    std::array<CanFilter, kMaxCanFilters> filters_{};
    std::size_t filter_count_ = 0;
    CanFrameQueue<kQueueDepth> rx_;
    CanHealth health_;
  };

  CanLoopbackBus() = default;
  CanLoopbackBus(const CanLoopbackBus&) = delete;
  CanLoopbackBus& operator=(const CanLoopbackBus&) = delete;

  // A new endpoint; no filters accepts every frame. Fails when the table is full
  // or more than kMaxCanFilters filters are given.
  Result<Endpoint*> attach(std::span<const CanFilter> filters = {});

  // Fault injection (tests): bus-off refuses the endpoint's sends until cleared;
  // an injected error frame (CAN_ERR_* class bits, the 8 data bytes of a
  // SocketCAN error frame) is folded in as SocketCAN does: counted, and the
  // controller state follows (CAN_ERR_CRTL warning/passive, CAN_ERR_BUSOFF,
  // CAN_ERR_RESTARTED).
  void set_bus_off(Endpoint& endpoint, bool bus_off);
  void inject_error_frame(Endpoint& endpoint, std::uint32_t error_class,
                          const std::array<std::uint8_t, 8>& data = {});

  // Frames carried since construction (every send, whoever received it).
  std::uint32_t frames_carried() const;

 private:
  mutable std::mutex mutex_;
  std::condition_variable arrived_;
  std::array<Endpoint, kMaxEndpoints> endpoints_{};
  std::size_t count_ = 0;
  std::uint32_t carried_ = 0;
};

}  // namespace petra::hal
