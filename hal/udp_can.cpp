#include "hal/udp_can.hpp"

#include <cstdlib>
#include <cstring>

namespace petra::hal {

namespace {

constexpr std::uint32_t kExtendedFlag = 1u << 31;
constexpr std::uint32_t kRtrFlag = 1u << 30;
constexpr char kPrefix[] = "udp:";

// "NNNNN" then `end`: a port 1..65535, or 0 when malformed.
std::uint16_t parse_port(const char* text, char end, const char** after) {
  unsigned long v = 0;
  int digits = 0;
  for (; *text >= '0' && *text <= '9' && digits < 6; ++text, ++digits)
    v = v * 10 + static_cast<unsigned long>(*text - '0');
  if (digits == 0 || *text != end || v == 0 || v > 65535) return 0;
  *after = text;
  return static_cast<std::uint16_t>(v);
}

}  // namespace

bool is_udp_can_spec(const char* interface) {
  return std::strncmp(interface, kPrefix, sizeof(kPrefix) - 1) == 0;
}

Result<UdpCanSpec> parse_udp_can_spec(const char* interface) {
  if (!is_udp_can_spec(interface))
    return Error::make(Errc::parse_error, "'%s': not udp:LOCAL_PORT:PEER_PORT", interface);
  const char* p = interface + sizeof(kPrefix) - 1;
  UdpCanSpec spec;
  spec.local_port = parse_port(p, ':', &p);
  if (spec.local_port != 0) spec.peer_port = parse_port(p + 1, '\0', &p);
  if (spec.local_port == 0 || spec.peer_port == 0)
    return Error::make(Errc::parse_error, "'%s': expected udp:LOCAL_PORT:PEER_PORT, ports 1..65535",
                       interface);
  return spec;
}

void encode_udp_can(const CanFrame& frame, std::span<std::uint8_t, kUdpCanDatagramBytes> out) {
  std::uint32_t id = frame.id;
  if (frame.extended) id |= kExtendedFlag;
  if (frame.rtr) id |= kRtrFlag;
  for (int k = 0; k < 4; ++k)
    out[static_cast<std::size_t>(k)] = static_cast<std::uint8_t>(id >> (8 * k));
  out[4] = frame.len;
  out[5] = out[6] = out[7] = 0;
  for (std::size_t k = 0; k < 8; ++k) out[8 + k] = frame.data[k];
}

Result<CanFrame> decode_udp_can(std::span<const std::uint8_t> d) {
  if (d.size() != kUdpCanDatagramBytes)
    return Error::make(Errc::parse_error, "can/udp: datagram of %zu bytes, expected %zu", d.size(),
                       kUdpCanDatagramBytes);
  if (d[5] != 0 || d[6] != 0 || d[7] != 0)
    return Error::make(Errc::parse_error, "can/udp: reserved bytes 5..7 not zero");
  std::uint32_t id = 0;
  for (int k = 0; k < 4; ++k) id |= std::uint32_t{d[static_cast<std::size_t>(k)]} << (8 * k);
  CanFrame f;
  f.extended = (id & kExtendedFlag) != 0;
  f.rtr = (id & kRtrFlag) != 0;
  if ((id & (1u << 29)) != 0)
    return Error::make(Errc::parse_error, "can/udp: id bit 29 set (error frames are not carried)");
  f.id = id & CanFrame::kExtendedIdMask;
  f.len = d[4];
  for (std::size_t k = 0; k < 8; ++k) f.data[k] = d[8 + k];
  PETRA_TRY(validate_frame(f));
  return f;
}

Status UdpCanPort::open(const UdpCanSpec& spec) {
  health_ = {};
  PETRA_TRY(link_.open("127.0.0.1", spec.local_port));
  PETRA_TRY(link_.set_peer("127.0.0.1", spec.peer_port));
  // Room for bursts (five drives' configuration answers) without drops.
  link_.set_receive_buffer(1 << 18);
  link_.set_send_buffer(1 << 18);
  return {};
}

Status UdpCanPort::send(const CanFrame& frame) {
  if (!link_.is_open()) return Error::make(Errc::not_ready, "can/udp: not open");
  PETRA_TRY(validate_frame(frame));
  std::array<std::uint8_t, kUdpCanDatagramBytes> buf{};
  encode_udp_can(frame, buf);
  switch (link_.send(buf)) {
    case SendResult::sent:
      ++health_.frames_sent;
      return {};
    case SendResult::would_block:
      ++health_.tx_dropped;
      return Error::make(Errc::capacity_exceeded, "can/udp: socket buffer full, frame 0x%X dropped",
                         frame.id);
    case SendResult::error:
      break;
  }
  ++health_.tx_dropped;
  return Error::make(Errc::io_error, "can/udp: send of frame 0x%X failed", frame.id);
}

Result<bool> UdpCanPort::receive(CanFrame& out, int timeout_ms) {
  if (!link_.is_open()) return Error::make(Errc::not_ready, "can/udp: not open");
  std::array<std::uint8_t, 64> buf{};
  // A malformed datagram is dropped and the wait goes on with what is left
  // of it (bounded: each pass consumes one datagram or ends the wait).
  for (int pass = 0; pass < 64; ++pass) {
    auto n = timeout_ms > 0 && pass == 0 ? link_.receive_wait(buf, timeout_ms) : link_.receive(buf);
    if (!n) return n.error();
    if (!n->got) return false;  // nothing waiting; an empty datagram is malformed
    const std::size_t size = n->size;
    auto f = decode_udp_can(
        std::span<const std::uint8_t>(buf.data(), size > buf.size() ? buf.size() : size));
    if (size > buf.size() || !f) {
      ++health_.rx_dropped;
      continue;
    }
    out = *f;
    ++health_.frames_received;
    return true;
  }
  return false;
}

}  // namespace petra::hal
