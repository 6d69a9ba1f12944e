// A non-blocking UDP endpoint for CCSDS packets: bound to a local port for
// commands, sending to one peer for telemetry. Numeric IPv4 addresses (or
// "localhost") only, so no resolver (and no heap) is involved. Sending never
// blocks: a full socket buffer is reported as would_block. Receiving tells
// "nothing waiting" from an empty datagram, and counts the datagrams the kernel
// dropped because the receive buffer was full (SO_RXQ_OVFL).
#pragma once

#include <netinet/in.h>

#include <cstddef>
#include <cstdint>
#include <span>

#include "algo/core/result.hpp"

namespace petra::hal {

enum class SendResult : std::uint8_t { sent, would_block, error };

// One receive: `got` false when nothing was waiting (or the wait timed out);
// otherwise `size` is the datagram's true size, 0 for an empty datagram, more
// than the buffer when it was truncated.
struct Received {
  bool got = false;
  std::size_t size = 0;
};

class UdpLink {
 public:
  UdpLink() = default;
  ~UdpLink();
  UdpLink(const UdpLink&) = delete;
  UdpLink& operator=(const UdpLink&) = delete;

  // Opens a socket bound to host:port (port 0 picks a free port).
  Status open(const char* host, std::uint16_t port);
  // Destination of send().
  Status set_peer(const char* host, std::uint16_t port);
  // Enlarge the kernel buffers (telemetry bursts, command bursts); best effort.
  void set_send_buffer(int bytes);
  void set_receive_buffer(int bytes);

  // One datagram into buf, never blocking.
  Result<Received> receive(std::span<std::uint8_t> buf);
  SendResult send(std::span<const std::uint8_t> datagram);
  // Receive, waiting at most timeout_ms (ground tools).
  Result<Received> receive_wait(std::span<std::uint8_t> buf, int timeout_ms);
  // Datagrams the kernel dropped on this socket (full receive buffer) since it
  // was opened, as Linux reports it with each datagram (the count when that
  // datagram was queued: drops show with the next datagram received).
  std::uint32_t kernel_drops() const { return kernel_drops_; }

  std::uint16_t local_port() const;
  bool is_open() const { return fd_ >= 0; }
  void close();

 private:
  int fd_ = -1;
  sockaddr_in peer_{};
  bool has_peer_ = false;
  std::uint32_t kernel_drops_ = 0;
};

// Parses a numeric IPv4 address or "localhost".
Result<in_addr> parse_ipv4(const char* host);

}  // namespace petra::hal
