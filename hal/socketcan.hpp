// SocketCAN backend (Linux raw CAN socket): the rover's CAN controller, or vcan
// in the HIL bench. Non-blocking socket; kernel-side receive filters; error
// frames enabled and folded into CanHealth (warning, passive, bus-off,
// restarted); kernel receive overruns counted (SO_RXQ_OVFL). Frames the kernel
// cannot take now (EAGAIN, ENOBUFS) wait in a bounded send queue, retried on
// every send() and receive(); a full queue refuses the frame (tx_dropped).
// Memory: the queue is a member (kTxQueueDepth frames); open() does no heap work.
// Hosts without AF_CAN (this container's kernel): open() fails with io_error
// and socketcan_available() is false; the tests skip and the HIL bench runs them.
#pragma once

#include <cstdint>
#include <span>

#include "hal/can.hpp"
#include "hal/can_frame_queue.hpp"

namespace petra::hal {

// True when this kernel can create a CAN_RAW socket.
bool socketcan_available();

// Folds one SocketCAN error frame (can_id with CAN_ERR_FLAG, its 8 data bytes)
// into `health`: counts it, tracks the controller state. Pure; no OS calls.
void apply_error_frame(std::uint32_t can_id, std::span<const std::uint8_t, 8> data,
                       CanHealth& health);

class SocketCanPort final : public CanPort {
 public:
  static constexpr std::size_t kTxQueueDepth = 64;

  SocketCanPort() = default;
  SocketCanPort(const SocketCanPort&) = delete;
  SocketCanPort& operator=(const SocketCanPort&) = delete;
  ~SocketCanPort() override;

  // Opens and binds `interface` (e.g. "can0", "vcan0"); at most kMaxCanFilters
  // filters (none: every frame).
  Status open(const char* interface, std::span<const CanFilter> filters = {});
  void close();
  bool is_open() const { return fd_ >= 0; }

  Status send(const CanFrame& frame) override;
  Result<bool> receive(CanFrame& out, int timeout_ms) override;
  CanHealth health() const override { return health_; }

 private:
  Status flush_queue();
  Status write_now(const CanFrame& frame, bool& would_block);

  int fd_ = -1;
  CanFrameQueue<kTxQueueDepth> tx_;
  CanHealth health_;
  std::uint32_t kernel_drops_ = 0;  // last SO_RXQ_OVFL counter seen
};

}  // namespace petra::hal
