#include "tlm/telemetry.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "tests/support/heap_counter.hpp"
#include "tlm/tlm_queue.hpp"

namespace petra::tlm {
namespace {

TEST(Telemetry, EveryPacketRoundTripsWithHeaderTimeAndCrc) {
  GrindPlane g;
  g.eval_id = 3;
  g.rank = 1;
  g.normal = {0.1, -0.2, 0.97};
  g.centroid_mm = {1.25, 2.5, 800.125};
  g.area_mm2 = 1234.5;
  g.verdict = 0;
  g.plane_source = 1;
  g.normal_sigma_deg = 0.25f;
  g.offset_sigma_mm = 0.125f;
  g.footprint_rms_mm = 0.5f;
  g.footprint_diameter_mm = 20.0f;
  g.footprint_reach = 2;
  std::vector<std::uint8_t> buf(kMaxTmBytes);
  const std::size_t n =
      encode_tm(g, 42, wire::SeqFlags::unsegmented, TmTime{1700000000, 250000}, buf);
  ASSERT_EQ(n, kTmHeaderBytes + GrindPlane::wire_bytes() + kTmCrcBytes);
  auto p = decode_tm(std::span(buf).first(n));
  ASSERT_TRUE(p.ok()) << p.error().message;
  EXPECT_EQ(p->header.primary.apid, static_cast<std::uint16_t>(Apid::GRIND_PLANE));
  EXPECT_EQ(p->header.primary.seq_count, 42);
  EXPECT_EQ(p->header.time.seconds, 1700000000u);
  EXPECT_EQ(p->header.time.micros, 250000u);
  const auto& d = std::get<GrindPlane>(p->body);
  EXPECT_EQ(d.normal, g.normal);
  EXPECT_EQ(d.centroid_mm, g.centroid_mm);
  EXPECT_EQ(d.area_mm2, g.area_mm2);
  EXPECT_EQ(d.rank, 1);
  EXPECT_EQ(d.plane_source, 1);
  EXPECT_EQ(d.normal_sigma_deg, 0.25f);
  EXPECT_EQ(d.offset_sigma_mm, 0.125f);
  EXPECT_EQ(d.footprint_rms_mm, 0.5f);
  EXPECT_EQ(d.footprint_diameter_mm, 20.0f);
  EXPECT_EQ(d.footprint_reach, 2);
}

TEST(Telemetry, DecoderRefusesCorruptionNamingTheCheck) {
  Ack a;
  std::vector<std::uint8_t> buf(kMaxTmBytes);
  const std::size_t n = encode_tm(a, 0, wire::SeqFlags::unsegmented, {}, buf);
  buf.resize(n);
  auto bad = buf;
  bad[16] ^= 1;
  auto p = decode_tm(bad);
  ASSERT_FALSE(p.ok());
  EXPECT_NE(std::string(p.error().message).find("CRC"), std::string::npos);
  p = decode_tm(std::span(buf).first(n - 1));
  ASSERT_FALSE(p.ok());
  EXPECT_NE(std::string(p.error().message).find("length"), std::string::npos);
  EXPECT_FALSE(decode_tm(std::span(buf).first(5)).ok());
}

TEST(TlmQueue, CountsDropsWhenFullAndKeepsPerApidSequenceCounts) {
  std::vector<std::uint8_t> storage(TlmQueue::bytes_for(4));
  std::vector<std::uint16_t> lengths(4);
  TlmQueue q;
  q.init(storage, lengths);
  petra::test::HeapScope scope;
  Event e;
  Ack a;
  EXPECT_TRUE(q.push(e, {}));
  EXPECT_TRUE(q.push(a, {}));
  EXPECT_TRUE(q.push(e, {}));
  EXPECT_TRUE(q.push(e, {}));
  EXPECT_FALSE(q.push(e, {}));
  EXPECT_EQ(q.dropped(), 1u);
  EXPECT_EQ(q.high_water(), 4u);
  std::uint16_t seqs[4];
  for (int i = 0; i < 4; ++i) {
    seqs[i] = wire::read_primary_header(q.front()).seq_count;
    q.pop();
  }
  EXPECT_EQ(scope.allocations(), 0u);
  EXPECT_EQ(seqs[0], 0);  // EVENT 0
  EXPECT_EQ(seqs[1], 0);  // ACK 0
  EXPECT_EQ(seqs[2], 1);  // EVENT 1
  EXPECT_EQ(seqs[3], 2);  // EVENT 2
  // The dropped EVENT spent count 3: the next one is 4, a gap the ground sees.
  EXPECT_TRUE(q.push(e, {}));
  EXPECT_EQ(wire::read_primary_header(q.front()).seq_count, 4);
  q.pop();
  EXPECT_TRUE(q.empty());
}

}  // namespace
}  // namespace petra::tlm
