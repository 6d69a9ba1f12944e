// Forged, replayed, truncated, wrong-CRC, unknown-function-code, out-of-range
// and wrong-mode commands: each is rejected with its own reason event and
// REJECTED ack, the counters move as specified and nothing else changes.
#include <gtest/gtest.h>

#include <set>

#include "algo/wire/crc16.hpp"
#include "tests/fsw/executive_harness.hpp"

namespace petra::test {
namespace {

using cmd::FunctionCode;

struct Snapshot {
  Mode mode;
  fsw::CommandCounters cmd;
  std::array<double, kParamCount> params;
  std::uint32_t frames;
  std::uint32_t evaluations;
};

Snapshot snap(fsw::Executive& e) {
  Snapshot s{
      e.mode(), e.command_counters(), {}, e.loop_counters().frames, e.loop_counters().evaluations};
  for (std::size_t i = 0; i < kParamCount; ++i)
    (void)e.params().get(kParamTable[i].id, s.params[i]);
  return s;
}

void resign(std::vector<std::uint8_t>& p) {
  const std::size_t mac_at = p.size() - cmd::kCrcBytes - cmd::kHmacBytes;
  const cmd::AuthKey key = *cmd::parse_key_hex(std::span<const char>(kKeyHex, 64));
  const cmd::Mac mac = cmd::compute_mac(key, std::span(p).first(mac_at));
  std::copy(mac.begin(), mac.end(), p.begin() + static_cast<long>(mac_at));
  const std::uint16_t crc = wire::crc16_ccitt(std::span(p).first(p.size() - 2));
  p[p.size() - 2] = static_cast<std::uint8_t>(crc >> 8);
  p[p.size() - 1] = static_cast<std::uint8_t>(crc);
}

struct Case {
  const char* what;
  Reason reason;
  bool consumes_counter;  // authentic: the counter is used up
};

TEST(CommandRejection, EachBadCommandHasItsOwnReasonEventAndChangesNothingElse) {
  ExecutiveHarness h;
  ASSERT_TRUE(h.boot().ok());
  // A known good state first: one accepted command (its packet is replayed below).
  const auto first = h.make(FunctionCode::NOOP);
  const auto first_packet = h.packet(first);
  h.send_raw(first_packet);
  ASSERT_TRUE(h.cycle_until([&] { return h.has_ack(first.counter, AckStage::COMPLETED); }));
  // Into SAFE so SELECT_ROI is a wrong-mode command.
  cmd::SetModeArgs safe;
  safe.mode = static_cast<std::uint8_t>(Mode::SAFE);
  const auto to_safe = h.make(FunctionCode::SET_MODE, safe);
  h.send(to_safe);
  ASSERT_TRUE(h.cycle_until([&] { return h.has_ack(to_safe.counter, AckStage::COMPLETED); }));
  ASSERT_EQ(h.exec().mode(), Mode::SAFE);

  std::set<std::uint16_t> reason_events;
  const Case cases[] = {
      {"forged", Reason::BAD_AUTH, false},
      {"replayed", Reason::REPLAY, false},
      {"truncated", Reason::LENGTH_MISMATCH, false},
      {"wrong CRC", Reason::BAD_CRC, false},
      {"unknown function code", Reason::UNKNOWN_FUNCTION, true},
      {"out of range", Reason::OUT_OF_RANGE, true},
      {"wrong mode", Reason::WRONG_MODE, true},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.what);
    std::vector<std::uint8_t> p;
    const std::string what = c.what;
    if (what == "forged") {
      p = h.packet(h.make(FunctionCode::NOOP));
      p[15] ^= 0x5A;  // inside the MAC
      const std::uint16_t crc = wire::crc16_ccitt(std::span(p).first(p.size() - 2));
      p[p.size() - 2] = static_cast<std::uint8_t>(crc >> 8);
      p[p.size() - 1] = static_cast<std::uint8_t>(crc);
      --h.counter;  // the forged counter is not used up
    } else if (what == "replayed") {
      p = first_packet;
    } else if (what == "truncated") {
      p = h.packet(h.make(FunctionCode::SELECT_ROI, roi(10, 10, 50, 50, 2)));
      p.resize(p.size() - 3);
      --h.counter;
    } else if (what == "wrong CRC") {
      p = h.packet(h.make(FunctionCode::NOOP));
      p.back() ^= 0xFF;
      --h.counter;
    } else if (what == "unknown function code") {
      p = h.packet(h.make(FunctionCode::NOOP));
      p[6] = 0x6F;
      resign(p);
    } else if (what == "out of range") {
      cmd::SetModeArgs m;
      m.mode = 9;
      p = h.packet(h.make(FunctionCode::SET_MODE, m));
    } else {
      p = h.packet(h.make(FunctionCode::SELECT_ROI, roi(10, 10, 50, 50, 2)));
    }
    const Snapshot before = snap(h.exec());
    const std::size_t acks_before = h.all<tlm::Ack>().size();
    const fsw::EventLog& log = h.exec().events();
    const std::uint32_t events_before = log.total();
    const std::uint16_t reason_event = rejection_event(c.reason);
    const std::size_t reason_before = log.count(reason_event);
    const std::size_t overruns_before =
        log.count(static_cast<std::uint16_t>(EventId::CYCLE_OVERRUN));
    h.send_raw(p);
    ASSERT_TRUE(h.cycle_until([&] { return h.all<tlm::Ack>().size() > acks_before; }));
    const Snapshot after = snap(h.exec());

    const tlm::Ack ack = h.all<tlm::Ack>().back();
    EXPECT_EQ(ack.stage, static_cast<std::uint8_t>(AckStage::REJECTED));
    EXPECT_EQ(ack.reason, static_cast<std::uint8_t>(c.reason));
    if (what == "replayed") {
      EXPECT_EQ(ack.counter, first.counter);  // authentic, so reported
    }
    // That event and no other; the harness runs on the host's clock, so a
    // cycle the loaded host stretched past the period adds CYCLE_OVERRUN,
    // which is the clock's and not the command's.
    const std::size_t overruns =
        log.count(static_cast<std::uint16_t>(EventId::CYCLE_OVERRUN)) - overruns_before;
    EXPECT_EQ(log.count(reason_event), reason_before + 1);
    EXPECT_EQ(log.total(), events_before + 1 + overruns);
    reason_events.insert(reason_event);

    EXPECT_EQ(after.cmd.received, before.cmd.received + 1);
    EXPECT_EQ(after.cmd.rejected, before.cmd.rejected + 1);
    EXPECT_EQ(after.cmd.accepted, before.cmd.accepted);
    EXPECT_EQ(after.cmd.completed, before.cmd.completed);
    EXPECT_EQ(after.cmd.failed, before.cmd.failed);
    EXPECT_EQ(after.cmd.last_reason, c.reason);
    EXPECT_EQ(after.cmd.last_counter, c.consumes_counter ? h.counter : before.cmd.last_counter);
    EXPECT_EQ(after.mode, before.mode);
    EXPECT_EQ(after.params, before.params);
    EXPECT_EQ(after.frames, before.frames);
    EXPECT_EQ(after.evaluations, before.evaluations);
  }
  EXPECT_EQ(reason_events.size(), std::size(cases));  // every reason its own event
}

TEST(CommandRejection, OversizeDatagramIsTooLong) {
  ExecutiveHarness h;
  ASSERT_TRUE(h.boot().ok());
  h.send_raw(std::vector<std::uint8_t>(4000, 0xAB));
  ASSERT_TRUE(h.cycle_until([&] { return !h.all<tlm::Ack>().empty(); }));
  EXPECT_EQ(h.all<tlm::Ack>().back().reason, static_cast<std::uint8_t>(Reason::TOO_LONG));
}

}  // namespace
}  // namespace petra::test
