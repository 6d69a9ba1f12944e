// No heap after init: 12,000 commands, every kind in turn (valid and invalid;
// 800 of each of the 15 kinds: the count stays what 1,000 of the first 12 gave,
// as each costs a loop cycle)
// through the real UDP path allocate nothing, in the loop or on the worker
// thread, and resident memory stays flat.
#include <gtest/gtest.h>

#include <fstream>

#include "tests/fsw/executive_harness.hpp"
#include "tests/support/heap_counter.hpp"

namespace petra::test {
namespace {

using cmd::FunctionCode;

long resident_kb() {
  std::ifstream f("/proc/self/status");
  std::string line;
  while (std::getline(f, line))
    if (line.rfind("VmRSS:", 0) == 0) return std::stol(line.substr(6));
  return -1;
}

TEST(ExecutiveMemory, TwelveThousandCommandsOfEveryKindAllocateNothingAfterInit) {
  ExecutiveHarness h;
  fsw::EvalOutput o;
  tlm::GrindPlane p;
  p.normal = {0, 0, -1};
  (void)o.planes.push_back(p);
  h.job.script = o;
  h.job.proposals.count = 1;  // PROPOSE lists one rock: packet, picture, pick
  h.job.proposals.items[0].rock = RockCandidate{Rect{10, 10, 64, 48}, 40, 30, 20.0, 80.0, 500};
  h.job.proposals.items[0].planes_c = 2;
  ASSERT_TRUE(h.boot().ok());

  // Every packet is built before measuring (the ground side may allocate).
  std::vector<std::vector<std::uint8_t>> packets;
  constexpr std::size_t kPackets = 12000;
  for (int round = 0; packets.size() < kPackets; ++round) {
    for (const cmd::CommandDesc& d : cmd::command_table()) {
      const auto code = static_cast<FunctionCode>(d.code);
      cmd::Args args = cmd::default_args(code);
      if (code == FunctionCode::SELECT_ROI) args = roi(10, 10, 64, 48, 2);
      if (code == FunctionCode::SET_PARAM) args = cmd::SetParamArgs{5, 0.2};
      if (code == FunctionCode::GET_PARAM) args = cmd::GetParamArgs{1};
      if (code == FunctionCode::PROPOSE) args = cmd::ProposeArgs{0, 0, 0, 0, 0, 2, 1, 1, 0, 0};
      // Picks name the list of the PROPOSE before them (ids count from 1 at boot).
      if (code == FunctionCode::SELECT_PROPOSAL)
        args = cmd::SelectProposalArgs{static_cast<std::uint32_t>(round + 1), 1};
      if (code == FunctionCode::SET_MODE)
        args = cmd::SetModeArgs{static_cast<std::uint8_t>(round % 2 ? 1 : 5)};
      auto pk = h.packet(h.make(code, args));
      if (round % 5 == 4) pk[pk.size() / 2] ^= 1;  // every fifth round corrupted: rejections too
      packets.push_back(pk);
    }
  }
  // Warm-up: the first evaluation and product stream, outside the measurement.
  for (std::size_t i = 0; i < cmd::command_table().size(); ++i) h.send_raw(packets[i]);
  for (int i = 0; i < 50; ++i) {
    h.exec().run_cycle();
    usleep(1000);
  }
  std::uint8_t sink[2048];
  while (h.ground_.receive(sink)->got) {
  }
  const long rss_before = resident_kb();

  std::size_t telemetry = 0;
  std::size_t accepted = 0;
  std::size_t rejected = 0;
  std::size_t unreported = 0;  // throttled rejections: counted, no ack (RejectionThrottle)
  // Counts telemetry and acknowledgements without allocating (decode_tm is heap-free).
  auto drain = [&] {
    for (auto n = h.ground_.receive(sink); n.ok() && n->got; n = h.ground_.receive(sink)) {
      ++telemetry;
      auto pk = tlm::decode_tm(std::span<const std::uint8_t>(sink, n->size));
      if (!pk) continue;
      if (const auto* a = std::get_if<tlm::Ack>(&pk->body)) {
        if (a->stage == static_cast<std::uint8_t>(AckStage::ACCEPTED)) ++accepted;
        if (a->stage == static_cast<std::uint8_t>(AckStage::REJECTED)) ++rejected;
      }
    }
  };
  {
    HeapScope scope;
    for (std::size_t i = cmd::command_table().size(); i < packets.size(); ++i) {
      h.send_raw(packets[i]);
      const std::uint32_t before = h.exec().command_counters().unreported;
      h.exec().run_cycle();
      const std::uint32_t after = h.exec().command_counters().unreported;
      unreported += after >= before ? after - before : after;  // RESET_COUNTERS zeroes it
      drain();
      if (i % 64 == 0) usleep(500);  // let the worker finish evaluations now and then
    }
    for (int i = 0; i < 200 && (h.exec().evaluation_running() || i < 20); ++i) {
      h.exec().run_cycle();
      drain();
      usleep(1000);
    }
    EXPECT_EQ(scope.allocations(), 0u);
  }
  const long rss_after = resident_kb();
  // Every command got exactly one ACCEPTED or REJECTED acknowledgement, or was
  // counted as a throttled rejection (the counters themselves are zeroed by
  // each RESET_COUNTERS in the mix).
  const std::size_t sent = packets.size() - cmd::command_table().size();
  EXPECT_EQ(accepted + rejected + unreported, sent);
  EXPECT_GT(unreported, 0u);
  EXPECT_GT(accepted, sent / 2);
  EXPECT_GT(rejected, sent / 10);  // corrupted rounds, wrong modes, BUSY
  EXPECT_GT(h.job.runs.load(), 1);
  EXPECT_GT(telemetry, packets.size());
  // Flat: every buffer was touched at init. 64 kB of slack for the test's own stack and libc.
  // Under ASan the sanitizer's quarantine and shadow pages move RSS; there the heap counter
  // (every allocation, malloc included) is the proof, checked above.
#if !defined(__SANITIZE_ADDRESS__)
  EXPECT_LE(rss_after - rss_before, 64) << "RSS " << rss_before << " kB -> " << rss_after << " kB";
#endif
  std::printf(
      "[ figures  ] %zu commands, %zu accepted, %zu rejected (+%zu throttled), %d evaluations, "
      "%zu telemetry packets, "
      "RSS %ld -> %ld kB, %zu bytes allocated at init\n",
      sent, accepted, rejected, unreported, h.job.runs.load(), telemetry, rss_before, rss_after,
      h.exec().memory_bytes());
}

}  // namespace
}  // namespace petra::test
