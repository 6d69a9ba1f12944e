// libFuzzer target over the telemetry decoder (tlm/telemetry: what `petra tlm`
// and the ground station run on every datagram). Two ways in:
//  - raw: the input is a datagram as received;
//  - framed: byte 0 picks a packet type, the rest fills its header fields and
//    payload, and the length field and CRC are made right, so the fuzzer
//    reaches every packet's field decoding.
// Properties: no crash or sanitizer report; a framed packet decodes, and
// re-encodes to exactly the bytes that were decoded.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <span>
#include <variant>

#include "algo/wire/ccsds.hpp"
#include "algo/wire/crc16.hpp"
#include "tlm/telemetry.hpp"

namespace {

void check(bool ok, const char* what) {
  if (!ok) {
    std::fprintf(stderr, "fuzz property violated: %s\n", what);
    std::abort();
  }
}

// Re-encodes a decoded packet with its own header values.
std::size_t reencode(const petra::tlm::TmPacket& p, std::span<std::uint8_t> out) {
  return std::visit(
      [&](const auto& body) -> std::size_t {
        using B = std::decay_t<decltype(body)>;
        if constexpr (std::is_same_v<B, std::monostate>) {
          return 0;
        } else {
          return petra::tlm::encode_tm(body, p.header.primary.seq_count, p.header.primary.seq_flags,
                                       p.header.time, out);
        }
      },
      p.body);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace petra;
  const std::span<const std::uint8_t> in(data, size);
  if (size == 0 || (data[0] & 0x80) != 0) {
    (void)tlm::decode_tm(in);
    return 0;
  }
  const auto table = tlm::telemetry_table();
  const tlm::TmDesc& desc = table[data[0] % table.size()];
  static std::uint8_t p[tlm::kMaxTmBytes];
  const std::size_t total = tlm::kTmHeaderBytes + desc.payload_bytes + tlm::kTmCrcBytes;
  std::memset(p, 0, total);
  // Bytes 1..: sequence count and flags (2), time (8), payload.
  const std::size_t body = size - 1 < total - 8 ? size - 1 : total - 8;
  std::memcpy(p + 2, data + 1, body);
  wire::PrimaryHeader h = wire::read_primary_header(std::span<const std::uint8_t>(p, 6));
  h.version = 0;
  h.type = wire::PacketType::telemetry;
  h.secondary_header = true;
  h.apid = desc.apid;
  h.data_length = static_cast<std::uint16_t>(total - 7);
  wire::write_primary_header(h, std::span<std::uint8_t>(p, 6));
  const std::uint16_t crc = wire::crc16_ccitt(std::span<const std::uint8_t>(p, total - 2));
  p[total - 2] = static_cast<std::uint8_t>(crc >> 8);
  p[total - 1] = static_cast<std::uint8_t>(crc);
  const std::span<const std::uint8_t> packet(p, total);
  auto decoded = tlm::decode_tm(packet);
  check(decoded.ok(), "a well-framed packet did not decode");
  static std::uint8_t again[tlm::kMaxTmBytes];
  const std::size_t n = reencode(*decoded, again);
  check(n == total, "re-encoded size differs");
  check(std::memcmp(again, p, total) == 0, "re-encoding differs");
  return 0;
}
