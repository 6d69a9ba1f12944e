// CAN frames over UDP on the loopback interface: the arm's simulated drives
// (`petra sim arm --can udp:LOCAL:PEER`) as a separate process on hosts without AF_CAN, so
// that petra-fsw itself boots and moves the simulated arm (the ground
// station's end-to-end test, software-in-the-loop runs). Not a flight link:
// the rover uses SocketCAN (hal/socketcan.hpp).
// One datagram per frame, 16 bytes (docs/icd.md "CAN over UDP"):
//   u32 LE id | bit 31 extended | bit 30 rtr, u8 len, 3 zero bytes, 8 data bytes.
// Malformed datagrams change nothing and are counted in rx_dropped.
// send() never blocks: a full socket buffer refuses the frame (tx_dropped).
// Memory: the socket only; no heap.
#pragma once

#include <array>
#include <cstdint>
#include <span>

#include "algo/core/result.hpp"
#include "hal/can.hpp"
#include "hal/udp_link.hpp"

namespace petra::hal {

inline constexpr std::size_t kUdpCanDatagramBytes = 16;

// The interface name that selects this backend: "udp:LOCAL_PORT:PEER_PORT"
// (both 1..65535, on 127.0.0.1). Anything else not starting with "udp:" is
// a SocketCAN interface name.
struct UdpCanSpec {
  std::uint16_t local_port = 0;
  std::uint16_t peer_port = 0;
};
bool is_udp_can_spec(const char* interface);
Result<UdpCanSpec> parse_udp_can_spec(const char* interface);

// Frame <-> datagram (pure; decode validates everything).
void encode_udp_can(const CanFrame& frame, std::span<std::uint8_t, kUdpCanDatagramBytes> out);
Result<CanFrame> decode_udp_can(std::span<const std::uint8_t> datagram);

class UdpCanPort final : public CanPort {
 public:
  Status open(const UdpCanSpec& spec);
  void close() { link_.close(); }
  bool is_open() const { return link_.is_open(); }

  Status send(const CanFrame& frame) override;
  Result<bool> receive(CanFrame& out, int timeout_ms) override;
  CanHealth health() const override { return health_; }

 private:
  UdpLink link_;
  CanHealth health_;
};

}  // namespace petra::hal
