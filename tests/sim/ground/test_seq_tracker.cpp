// The ground sees every telemetry loss: the flight queue spends a sequence
// count on a packet it drops, and SeqTracker turns the hole into a gap.
#include "sim/ground/seq_tracker.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "sim/ground/tlm_format.hpp"
#include "tlm/tlm_queue.hpp"

namespace petra::ground {
namespace {

// Everything in the queue, as the ground would decode it.
std::vector<tlm::TmPacket> drain(tlm::TlmQueue& q) {
  std::vector<tlm::TmPacket> out;
  while (!q.empty()) {
    auto p = tlm::decode_tm(q.front());
    EXPECT_TRUE(p.ok()) << p.error().message;
    if (p) out.push_back(*p);
    q.pop();
  }
  return out;
}

TEST(SeqTracker, AFullFlightQueueLeavesAGapTheGroundCounts) {
  std::vector<std::uint8_t> storage(tlm::TlmQueue::bytes_for(4));
  std::vector<std::uint16_t> lengths(4);
  tlm::TlmQueue q;
  q.init(storage, lengths);
  tlm::Event e;
  tlm::Ack a;
  SeqTracker seqs;
  // 6 events into 4 slots: events 4 and 5 are dropped.
  for (int i = 0; i < 6; ++i) (void)q.push(e, {});
  EXPECT_EQ(q.dropped(), 2u);
  for (const auto& p : drain(q)) EXPECT_EQ(seqs.observe(p), 0u);
  // The loop drains; housekeeping reports the drops, then one more event.
  tlm::Housekeeping hk;
  hk.tlm_dropped = q.dropped();
  ASSERT_TRUE(q.push(hk, {}));
  ASSERT_TRUE(q.push(a, {}));
  ASSERT_TRUE(q.push(e, {}));
  const auto after = drain(q);
  ASSERT_EQ(after.size(), 3u);
  EXPECT_EQ(seqs.observe(after[0]), 0u);
  EXPECT_EQ(seqs.observe(after[1]), 0u);
  EXPECT_EQ(seqs.observe(after[2]), 2u);  // the two dropped events
  const ApidStats& ev = seqs.apids().at(static_cast<std::uint16_t>(tlm::Apid::EVENT));
  EXPECT_EQ(ev.received, 5u);
  EXPECT_EQ(ev.missing, 2u);
  EXPECT_EQ(ev.gaps, 1u);
  EXPECT_EQ(seqs.missing(), 2u);
  EXPECT_EQ(seqs.flight_dropped(), 2);
  EXPECT_NE(seqs.summary_line().find("2 missing in 1 gaps (EVENT 2)"), std::string::npos)
      << seqs.summary_line();
  EXPECT_NE(seqs.summary_line().find("flight dropped 2"), std::string::npos);
  const std::string j = seqs.summary_json();
  EXPECT_NE(j.find("\"missing\":2,\"bad\":0,\"flight_dropped\":2"), std::string::npos) << j;
  EXPECT_NE(j.find("{\"apid\":17,\"packet\":\"EVENT\",\"received\":5,\"missing\":2,\"gaps\":1"),
            std::string::npos)
      << j;
  // The packet after the gap says so in both output forms.
  EXPECT_NE(format_json(after[2], 2).find("\"seq\":6,\"missing_before\":2,"), std::string::npos);
  EXPECT_NE(format_line(after[2], 2).find("(GAP: 2 missing before)"), std::string::npos);
  EXPECT_EQ(format_json(after[1]).find("missing_before"), std::string::npos);
}

tlm::TmPacket event_with_seq(std::uint16_t seq) {
  tlm::TmPacket p;
  p.header.primary.apid = static_cast<std::uint16_t>(tlm::Apid::EVENT);
  p.header.primary.seq_count = seq;
  p.body = tlm::Event{};
  return p;
}

TEST(SeqTracker, CountWrapIsNoGapAndARestartIsNotALoss) {
  SeqTracker seqs;
  EXPECT_EQ(seqs.observe(event_with_seq(16382)), 0u);
  EXPECT_EQ(seqs.observe(event_with_seq(16383)), 0u);
  EXPECT_EQ(seqs.observe(event_with_seq(0)), 0u);  // 14-bit wrap
  EXPECT_EQ(seqs.observe(event_with_seq(3)), 2u);  // 1 and 2 lost
  EXPECT_EQ(seqs.observe(event_with_seq(0)), 0u);  // the service restarted
  const ApidStats& ev = seqs.apids().begin()->second;
  EXPECT_EQ(ev.missing, 2u);
  EXPECT_EQ(ev.restarts, 1u);
  seqs.bad_datagram();
  EXPECT_EQ(seqs.bad(), 1u);
  EXPECT_EQ(seqs.flight_dropped(), -1);  // no housekeeping yet
  EXPECT_NE(seqs.summary_json().find("\"flight_dropped\":null"), std::string::npos);
}

}  // namespace
}  // namespace petra::ground
