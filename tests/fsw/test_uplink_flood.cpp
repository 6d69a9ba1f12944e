// The uplink under bad traffic: empty and short datagrams are counted and
// refused like any other bad packet and never stop the drain; the drain is
// bounded per cycle; rejections anyone can cause are reported once per reason
// and second (event and ack) plus a summary of the rest; kernel drops on the
// command port reach housekeeping; none of it allocates.
#include <gtest/gtest.h>

#include "tests/fsw/executive_harness.hpp"
#include "tests/support/heap_counter.hpp"

namespace petra::test {
namespace {

using cmd::FunctionCode;

std::uint16_t id(EventId e) {
  return static_cast<std::uint16_t>(e);
}

std::size_t events_of(const ExecutiveHarness& h, std::uint16_t which) {
  std::size_t n = 0;
  for (const auto& e : h.all<tlm::Event>()) n += e.event_id == which ? 1 : 0;
  return n;
}

TEST(UplinkFlood, EmptyDatagramsAreRefusedAndTheCommandBehindThemRunsInTheSameCycle) {
  ExecutiveHarness h;
  ASSERT_TRUE(h.boot().ok());
  h.cycles(1);
  for (int i = 0; i < 20; ++i) h.send_raw({});
  h.send_raw({0x18, 0x64});  // a short one too
  const auto noop = h.make(FunctionCode::NOOP);
  h.send(noop);
  usleep(20000);  // loopback delivery
  h.cycles(1);
  EXPECT_TRUE(h.has_ack(noop.counter, AckStage::COMPLETED));
  const auto& c = h.exec().command_counters();
  EXPECT_EQ(c.received, 22u);
  EXPECT_EQ(c.rejected, 21u);
  EXPECT_EQ(c.unreported, 20u);  // one TOO_SHORT reported in full, 20 counted
  EXPECT_EQ(events_of(h, rejection_event(Reason::TOO_SHORT)), 1u);
  EXPECT_EQ(h.acks_for(0).size(), 1u);
  // When the second is over, one summary gives the number not reported.
  ASSERT_TRUE(h.cycle_until([&] { return h.has_event(id(EventId::CMD_REJECTS_UNREPORTED)); }));
  for (const auto& e : h.all<tlm::Event>()) {
    if (e.event_id != id(EventId::CMD_REJECTS_UNREPORTED)) continue;
    EXPECT_EQ(e.args[0], static_cast<std::int32_t>(Reason::TOO_SHORT));
    EXPECT_EQ(e.args[1], 20);
    EXPECT_EQ(e.args[2], 1000);
  }
  ASSERT_TRUE(h.cycle_until([&] {
    return !h.all<tlm::Housekeeping>().empty() && h.all<tlm::Housekeeping>().back().cycles > 2;
  }));
  EXPECT_EQ(h.all<tlm::Housekeeping>().back().cmd_unreported, 20u);
}

TEST(UplinkFlood, TheDrainIsBoundedPerCycle) {
  ExecutiveHarness h;
  h.loop = R"({"cycle_ms":10,"commands_per_cycle":16})";
  ASSERT_TRUE(h.boot().ok());
  for (int i = 0; i < 40; ++i) h.send_raw({});
  usleep(20000);
  h.cycles(1);
  EXPECT_EQ(h.exec().command_counters().received, 16u);
  h.cycles(2);
  EXPECT_EQ(h.exec().command_counters().received, 40u);
}

TEST(UplinkFlood, AuthenticatedRejectionsAreEachReported) {
  ExecutiveHarness h;
  ASSERT_TRUE(h.boot().ok());
  std::vector<std::uint32_t> counters;
  for (int i = 0; i < 3; ++i) {  // out of range: only a key holder can send these
    cmd::SetModeArgs m;
    m.mode = 9;
    const auto c = h.make(FunctionCode::SET_MODE, m);
    counters.push_back(c.counter);
    h.send(c);
  }
  ASSERT_TRUE(h.cycle_until([&] { return h.has_ack(counters.back(), AckStage::REJECTED); }));
  for (std::uint32_t c : counters) EXPECT_TRUE(h.has_ack(c, AckStage::REJECTED));
  EXPECT_EQ(events_of(h, rejection_event(Reason::OUT_OF_RANGE)), 3u);
  EXPECT_EQ(h.exec().command_counters().unreported, 0u);
}

TEST(UplinkFlood, ReplaysOfARecordedCommandAreThrottledLikeForgeries) {
  ExecutiveHarness h;
  ASSERT_TRUE(h.boot().ok());
  const auto noop = h.make(FunctionCode::NOOP);
  const auto recorded = h.packet(noop);
  h.send_raw(recorded);
  ASSERT_TRUE(h.cycle_until([&] { return h.has_ack(noop.counter, AckStage::COMPLETED); }));
  for (int i = 0; i < 50; ++i) h.send_raw(recorded);
  ASSERT_TRUE(h.cycle_until([&] { return h.exec().command_counters().received == 51; }));
  EXPECT_EQ(events_of(h, rejection_event(Reason::REPLAY)), 1u);
  std::size_t replay_acks = 0;
  for (const auto& a : h.acks_for(noop.counter))
    replay_acks += a.stage == static_cast<std::uint8_t>(AckStage::REJECTED) ? 1 : 0;
  EXPECT_EQ(replay_acks, 1u);
  EXPECT_EQ(h.exec().command_counters().unreported, 49u);
}

TEST(UplinkFlood, KernelDropsOnTheCommandPortReachHousekeeping) {
  ExecutiveHarness h;
  ASSERT_TRUE(h.boot().ok());
  constexpr std::uint32_t kBurst = 20000;  // far beyond the 256 KiB receive buffer
  for (std::uint32_t i = 0; i < kBurst; ++i) h.send_raw({});
  // Drain, then one more datagram: Linux reports the drops with the next one queued.
  ASSERT_TRUE(h.cycle_until([&] {
    const std::uint32_t before = h.exec().command_counters().received;
    h.cycles(3);
    return h.exec().command_counters().received == before;
  }));
  h.send_raw({});
  const std::uint32_t received_all = h.exec().command_counters().received + 1;
  ASSERT_TRUE(h.cycle_until([&] { return h.exec().command_counters().received == received_all; }));
  const std::uint32_t drops = h.exec().command_counters().kernel_drops;
  EXPECT_GT(drops, 0u);
  EXPECT_EQ(drops + received_all, kBurst + 1);
  ASSERT_TRUE(h.cycle_until([&] {
    return h.has_event(id(EventId::CMD_KERNEL_DROPS)) && !h.all<tlm::Housekeeping>().empty() &&
           h.all<tlm::Housekeeping>().back().cmd_kernel_drops == drops;
  }));
}

TEST(UplinkFlood, RefusingAndAcceptingAllocateNothing) {
  if (!counts_malloc()) GTEST_SKIP() << "malloc is owned by the sanitizer runtime";
  ExecutiveHarness h;
  ASSERT_TRUE(h.boot().ok());
  const auto warm = h.make(FunctionCode::NOOP);
  h.send(warm);
  ASSERT_TRUE(h.cycle_until([&] { return h.has_ack(warm.counter, AckStage::COMPLETED); }));
  std::vector<std::vector<std::uint8_t>> bad = {{}, {1, 2, 3}, std::vector<std::uint8_t>(300, 7)};
  auto forged = h.packet(h.make(FunctionCode::NOOP));
  forged[14] ^= 1;
  bad.push_back(forged);
  const auto noop = h.make(FunctionCode::NOOP);
  const auto good = h.packet(noop);
  for (int i = 0; i < 5; ++i)
    for (const auto& b : bad) h.send_raw(b);
  h.send_raw(good);
  usleep(20000);
  std::size_t allocations = 0;
  for (int i = 0; i < 5; ++i) {
    HeapScope heap;
    h.exec().run_cycle();
    allocations += heap.allocations();
    h.drain();
  }
  EXPECT_EQ(allocations, 0u);
  EXPECT_TRUE(h.has_ack(noop.counter, AckStage::COMPLETED));
}

}  // namespace
}  // namespace petra::test
