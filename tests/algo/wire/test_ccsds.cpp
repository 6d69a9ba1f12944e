#include "algo/wire/ccsds.hpp"

#include <gtest/gtest.h>

#include <array>

namespace petra::wire {
namespace {

TEST(Ccsds, PrimaryHeaderBitLayoutMatchesTheStandard) {
  PrimaryHeader h;
  h.type = PacketType::telecommand;
  h.secondary_header = true;
  h.apid = 0x064;
  h.seq_flags = SeqFlags::unsegmented;
  h.seq_count = 0x1234;
  h.data_length = 0x0041;
  std::array<std::uint8_t, 6> b{};
  write_primary_header(h, b);
  // 000 1 1 00001100100 | 11 01001000110100 | 0x0041
  EXPECT_EQ(b[0], 0x18);
  EXPECT_EQ(b[1], 0x64);
  EXPECT_EQ(b[2], 0xD2);
  EXPECT_EQ(b[3], 0x34);
  EXPECT_EQ(b[4], 0x00);
  EXPECT_EQ(b[5], 0x41);
}

TEST(Ccsds, RoundTripsEveryFieldAtItsLimits) {
  PrimaryHeader h;
  h.version = 0;
  h.type = PacketType::telemetry;
  h.secondary_header = false;
  h.apid = kMaxApid;
  h.seq_flags = SeqFlags::last;
  h.seq_count = kSeqCountMask;
  h.data_length = 0xFFFF;
  std::array<std::uint8_t, 6> b{};
  write_primary_header(h, b);
  const PrimaryHeader r = read_primary_header(b);
  EXPECT_EQ(r.version, 0);
  EXPECT_EQ(r.type, PacketType::telemetry);
  EXPECT_FALSE(r.secondary_header);
  EXPECT_EQ(r.apid, kMaxApid);
  EXPECT_EQ(r.seq_flags, SeqFlags::last);
  EXPECT_EQ(r.seq_count, kSeqCountMask);
  EXPECT_EQ(r.data_length, 0xFFFF);
  EXPECT_EQ(packet_bytes(r), kMaxPacketBytes);
}

}  // namespace
}  // namespace petra::wire
