// CAN bus access behind one small interface (classic CAN 2.0, 8-byte frames).
// Backends: SocketCAN (hal/socketcan.hpp, the rover and the HIL bench on vcan)
// and an in-process loopback bus (hal/can_loopback.hpp, tests and ground
// simulation). The CANopen master (fsw/arm/canopen_master.hpp) sees only CanPort.
//
// Semantics every backend keeps:
//   send()    never blocks; a frame the bus cannot take now is queued in a
//             bounded queue or refused with Errc::capacity_exceeded (counted).
//   receive() returns true with a frame, false when none arrived within
//             timeout_ms (0 = poll); an error value only when the port is broken.
//   Bus errors (error frames, error-passive, bus-off) are counted in CanHealth,
//   never delivered as data frames. A bus-off port refuses send() with
//   Errc::io_error until the controller restarts.
// Memory: fixed-size types; no heap after a backend's open().
#pragma once

#include <array>
#include <cstdint>

#include "algo/core/result.hpp"

namespace petra::hal {

struct CanFrame {
  static constexpr std::uint32_t kStandardIdMask = 0x7FF;
  static constexpr std::uint32_t kExtendedIdMask = 0x1FFFFFFF;
  std::uint32_t id = 0;  // 11-bit, or 29-bit when extended
  std::uint8_t len = 0;  // 0..8
  bool extended = false;
  bool rtr = false;  // remote request (CANopen: node guarding; not used by Petra)
  std::array<std::uint8_t, 8> data{};
};

// Rejects an id too wide for its format or a length over 8.
Status validate_frame(const CanFrame& frame);

// Accept a frame when (frame.id & mask) == (id & mask), as SocketCAN's CAN_RAW_FILTER.
struct CanFilter {
  std::uint32_t id = 0;
  std::uint32_t mask = 0;  // 0 accepts everything
};
inline constexpr std::size_t kMaxCanFilters = 8;
inline bool filter_accepts(const CanFilter& f, const CanFrame& frame) {
  return (frame.id & f.mask) == (f.id & f.mask);
}

enum class CanBusState : std::uint8_t {
  error_active = 0,   // normal
  error_warning = 1,  // an error counter passed 96
  error_passive = 2,  // passed 127: the node may not signal errors actively
  bus_off = 3,        // passed 255: the controller left the bus
};
const char* can_bus_state_name(CanBusState state);

// What went wrong on the bus, counted since open. Housekeeping reports it.
struct CanHealth {
  CanBusState state = CanBusState::error_active;
  std::uint32_t frames_sent = 0;
  std::uint32_t frames_received = 0;
  std::uint32_t tx_queued = 0;         // frames waiting in the backend's send queue now
  std::uint32_t tx_dropped = 0;        // refused: send queue full
  std::uint32_t rx_dropped = 0;        // lost: receive queue full or kernel overrun
  std::uint32_t error_frames = 0;      // error frames seen (any class)
  std::uint32_t bus_off_count = 0;     // times the controller went bus-off
  std::uint32_t restarts = 0;          // times it came back
  std::uint32_t last_error_class = 0;  // CAN_ERR_* class bits of the last error frame
};

class CanPort {
 public:
  virtual ~CanPort() = default;
  virtual Status send(const CanFrame& frame) = 0;
  virtual Result<bool> receive(CanFrame& out, int timeout_ms) = 0;
  virtual CanHealth health() const = 0;
};

}  // namespace petra::hal
