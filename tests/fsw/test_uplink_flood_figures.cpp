// The uplink's figures on loopback (docs/executive.md "Uplink under bad
// traffic"): the executive in its real 10 ms loop while another thread floods
// its command port, paced, for PETRA_FLOOD_SECONDS (default 5) per phase:
//   1. 300 empty datagrams/s, a signed NOOP every 250 ms: every NOOP must
//      complete; the time from send to COMPLETED is printed, not asserted;
//   2. 1,000 random datagrams/s (random length 0..300, random bytes): the
//      telemetry spent on rejection reports (REJECTED acks, rejection and
//      summary events) is counted and must stay within the throttle's bound
//      (per reason and window: one event, one ack, one summary).
// Loopback only, bounded, stops by itself.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <map>
#include <random>
#include <thread>

#include "tests/fsw/executive_harness.hpp"

namespace petra::test {
namespace {

using cmd::FunctionCode;
using Clock = std::chrono::steady_clock;

int seconds_per_phase() {
  const char* env = std::getenv("PETRA_FLOOD_SECONDS");
  const int s = env != nullptr ? std::atoi(env) : 5;
  return s > 0 && s <= 120 ? s : 5;
}

// Sends make(i) at `rate` per second until stop; counts what it sent.
template <class Make>
std::thread flood(std::uint16_t port, int rate, std::atomic<bool>& stop, std::atomic<long>& sent,
                  Make make) {
  return std::thread([port, rate, &stop, &sent, make]() mutable {
    hal::UdpLink link;
    if (!link.open("127.0.0.1", 0) || !link.set_peer("127.0.0.1", port)) return;
    const auto period = std::chrono::nanoseconds(1000000000L / rate);
    auto next = Clock::now();
    for (long i = 0; !stop.load(); ++i) {
      const std::vector<std::uint8_t> d = make(i);
      if (link.send(d) == hal::SendResult::sent) sent.fetch_add(1);
      next += period;
      std::this_thread::sleep_until(next);
    }
  });
}

// Runs the executive's cycles on the real 10 ms period for `seconds`; calls each_cycle(t).
template <class Each>
void run_loop(ExecutiveHarness& h, int seconds, Each each_cycle) {
  const auto start = Clock::now();
  auto next = start;
  while (Clock::now() - start < std::chrono::seconds(seconds)) {
    h.exec().run_cycle();
    h.drain();
    each_cycle(Clock::now());
    next += std::chrono::milliseconds(10);
    std::this_thread::sleep_until(next);
  }
}

constexpr std::size_t kEventBytes =
    tlm::kTmHeaderBytes + tlm::Event::wire_bytes() + tlm::kTmCrcBytes;
constexpr std::size_t kAckBytes = tlm::kTmHeaderBytes + tlm::Ack::wire_bytes() + tlm::kTmCrcBytes;

bool is_rejection_report(const tlm::TmPacket& p) {
  if (const auto* a = std::get_if<tlm::Ack>(&p.body))
    return a->stage == static_cast<std::uint8_t>(AckStage::REJECTED);
  if (const auto* e = std::get_if<tlm::Event>(&p.body))
    return e->event_id >= PETRA_REJECT_EVENT_BASE ||
           e->event_id == static_cast<std::uint16_t>(EventId::CMD_REJECTS_UNREPORTED);
  return false;
}

TEST(UplinkFloodFigures, SignedCommandsGetThroughEmptyDatagramsAndRejectionReportsStayBounded) {
  const int seconds = seconds_per_phase();
  ExecutiveHarness h;
  ASSERT_TRUE(h.boot().ok());
  const std::uint16_t port = h.exec().command_port();

  // Phase 1: 300 empty datagrams/s, a signed NOOP every 250 ms.
  std::atomic<bool> stop{false};
  std::atomic<long> empties{0};
  std::thread t1 =
      flood(port, 300, stop, empties, [](long) { return std::vector<std::uint8_t>{}; });
  std::map<std::uint32_t, Clock::time_point> sent_at;
  std::map<std::uint32_t, double> latency_ms;
  auto next_noop = Clock::now();
  run_loop(h, seconds, [&](Clock::time_point now) {
    if (now >= next_noop) {
      const auto noop = h.make(FunctionCode::NOOP);
      h.send(noop);
      sent_at[noop.counter] = now;
      next_noop = now + std::chrono::milliseconds(250);
    }
    for (const auto& [counter, at] : sent_at)
      if (latency_ms.count(counter) == 0 && h.has_ack(counter, AckStage::COMPLETED))
        latency_ms[counter] = std::chrono::duration<double, std::milli>(now - at).count();
  });
  stop = true;
  t1.join();
  h.cycles(5);
  double worst = 0;
  int within_1s = 0;
  for (const auto& [counter, ms] : latency_ms) {
    worst = std::max(worst, ms);
    within_1s += ms <= 1000.0 ? 1 : 0;
  }
  EXPECT_EQ(latency_ms.size(), sent_at.size()) << "signed NOOPs without COMPLETED";
  const auto& c1 = h.exec().command_counters();
  std::printf(
      "[ figures  ] phase 1, %d s: %ld empty datagrams (%.0f/s), %zu signed NOOPs, %zu completed, "
      "%d within 1 s, slowest %.1f ms; rejected %u, of them %u unreported; kernel drops %u\n",
      seconds, empties.load(), static_cast<double>(empties.load()) / seconds, sent_at.size(),
      latency_ms.size(), within_1s, worst, c1.rejected, c1.unreported, c1.kernel_drops);

  // Phase 2: 1,000 random datagrams/s; the downlink bytes that report rejections.
  const std::size_t first = h.received.size();
  stop = false;
  std::atomic<long> randoms{0};
  std::thread t2 = flood(port, 1000, stop, randoms, [rng = std::mt19937(24)](long) mutable {
    std::vector<std::uint8_t> d(rng() % 301);
    for (auto& b : d) b = static_cast<std::uint8_t>(rng());
    return d;
  });
  const auto phase2 = Clock::now();
  run_loop(h, seconds, [](Clock::time_point) {});
  stop = true;
  t2.join();
  // One more second of cycles: the last window's summaries.
  (void)h.cycle_until([&] { return Clock::now() - phase2 > std::chrono::seconds(seconds + 1); },
                      1000);
  const double elapsed = std::chrono::duration<double>(Clock::now() - phase2).count();
  std::size_t report_packets = 0, report_bytes = 0, all_bytes = 0;
  for (std::size_t i = first; i < h.received.size(); ++i) {
    const std::size_t bytes = wire::packet_bytes(h.received[i].header.primary);
    all_bytes += bytes;
    if (!is_rejection_report(h.received[i])) continue;
    ++report_packets;
    report_bytes += bytes;
  }
  // The throttle's bound: 7 reasons x (event + ack + summary) per started window.
  const double windows = elapsed + 1.0;
  EXPECT_LE(static_cast<double>(report_packets), 21.0 * windows);
  const auto& c2 = h.exec().command_counters();
  std::printf(
      "[ figures  ] phase 2, %.1f s: %ld random datagrams (%.0f/s); rejection reports %zu packets, "
      "%zu bytes (%.0f B/s), %.1f %% of the %zu telemetry bytes; one event and one ack each "
      "would be %.0f B/s; kernel drops %u\n",
      elapsed, randoms.load(), static_cast<double>(randoms.load()) / seconds, report_packets,
      report_bytes, static_cast<double>(report_bytes) / elapsed,
      100.0 * static_cast<double>(report_bytes) / static_cast<double>(all_bytes), all_bytes,
      static_cast<double>(randoms.load()) * static_cast<double>(kEventBytes + kAckBytes) / elapsed,
      c2.kernel_drops);
}

}  // namespace
}  // namespace petra::test
