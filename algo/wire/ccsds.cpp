#include "algo/wire/ccsds.hpp"

namespace petra::wire {

void write_primary_header(const PrimaryHeader& h, std::span<std::uint8_t> out) {
  const unsigned word0 =
      (static_cast<unsigned>(h.version & 0x7u) << 13) | (static_cast<unsigned>(h.type) << 12) |
      (static_cast<unsigned>(h.secondary_header ? 1u : 0u) << 11) | (h.apid & kMaxApid);
  const unsigned word1 = (static_cast<unsigned>(h.seq_flags) << 14) | (h.seq_count & kSeqCountMask);
  out[0] = static_cast<std::uint8_t>(word0 >> 8);
  out[1] = static_cast<std::uint8_t>(word0);
  out[2] = static_cast<std::uint8_t>(word1 >> 8);
  out[3] = static_cast<std::uint8_t>(word1);
  out[4] = static_cast<std::uint8_t>(h.data_length >> 8);
  out[5] = static_cast<std::uint8_t>(h.data_length);
}

PrimaryHeader read_primary_header(std::span<const std::uint8_t> in) {
  const unsigned word0 = (static_cast<unsigned>(in[0]) << 8) | in[1];
  const unsigned word1 = (static_cast<unsigned>(in[2]) << 8) | in[3];
  PrimaryHeader h;
  h.version = static_cast<std::uint8_t>(word0 >> 13);
  h.type = static_cast<PacketType>((word0 >> 12) & 1u);
  h.secondary_header = ((word0 >> 11) & 1u) != 0;
  h.apid = static_cast<std::uint16_t>(word0 & kMaxApid);
  h.seq_flags = static_cast<SeqFlags>(word1 >> 14);
  h.seq_count = static_cast<std::uint16_t>(word1 & kSeqCountMask);
  h.data_length = static_cast<std::uint16_t>((static_cast<unsigned>(in[4]) << 8) | in[5]);
  return h;
}

}  // namespace petra::wire
