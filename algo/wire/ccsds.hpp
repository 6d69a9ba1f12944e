// CCSDS space packet primary header (CCSDS 133.0-B-2), 6 bytes, big-endian:
//   version (3 bits, 0) | type (1: 0 telemetry, 1 telecommand) | secondary header flag (1)
//   | APID (11) | sequence flags (2) | sequence count (14) | data length (16: bytes after
//   the primary header minus one).
// Shared by telecommands (cmd/) and telemetry (tlm/).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

namespace petra::wire {

enum class PacketType : std::uint8_t { telemetry = 0, telecommand = 1 };

// Sequence flags: segmentation of a larger unit (products are chunked).
enum class SeqFlags : std::uint8_t { continuation = 0, first = 1, last = 2, unsegmented = 3 };

struct PrimaryHeader {
  std::uint8_t version = 0;
  PacketType type = PacketType::telemetry;
  bool secondary_header = true;
  std::uint16_t apid = 0;  // 0..2047
  SeqFlags seq_flags = SeqFlags::unsegmented;
  std::uint16_t seq_count = 0;    // 0..16383, wraps
  std::uint16_t data_length = 0;  // total packet bytes - 7
};

inline constexpr std::size_t kPrimaryHeaderBytes = 6;
inline constexpr std::uint16_t kMaxApid = 0x7FF;
inline constexpr std::uint16_t kSeqCountMask = 0x3FFF;
inline constexpr std::size_t kMaxPacketBytes = 65542;  // 6 + 65536 (length field 0xFFFF)

// Writes 6 bytes into out (out.size() >= 6; apid and seq_count are masked).
void write_primary_header(const PrimaryHeader& h, std::span<std::uint8_t> out);
// Reads the first 6 bytes; in.size() >= 6 is the caller's check.
PrimaryHeader read_primary_header(std::span<const std::uint8_t> in);

// Total packet size implied by the header's data length field.
constexpr std::size_t packet_bytes(const PrimaryHeader& h) {
  return kPrimaryHeaderBytes + static_cast<std::size_t>(h.data_length) + 1;
}

}  // namespace petra::wire
