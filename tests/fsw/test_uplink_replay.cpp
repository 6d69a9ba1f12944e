// Replay protection that cannot be switched off by omission: the counter is
// kept beside the key when the configuration names no file, a missing or
// corrupt counter file stops the start until the operator gives a floor, and
// an exhausted counter (4294967295) is recovered by a new key.
#include <sys/stat.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "tests/fsw/executive_harness.hpp"

namespace petra::test {
namespace {

using cmd::FunctionCode;

const char* kNewKeyHex = "f0e1d2c3b4a5968778695a4b3c2d1e0f00112233445566778899aabbccddeeff";

std::filesystem::path scratch(const char* what) {
  auto dir = std::filesystem::temp_directory_path() /
             (std::string("petra_replay_") + what + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  return dir;
}

// Sends one command and waits for its final acknowledgement; returns its reason.
Reason final_reason(ExecutiveHarness& h, const std::vector<std::uint8_t>& packet,
                    std::uint32_t counter) {
  h.send_raw(packet);
  const bool done = h.cycle_until([&] {
    for (const auto& a : h.acks_for(counter))
      if (a.stage != static_cast<std::uint8_t>(AckStage::ACCEPTED)) return true;
    return false;
  });
  EXPECT_TRUE(done);
  return done ? static_cast<Reason>(h.acks_for(counter).back().reason) : Reason::NONE;
}

TEST(UplinkReplay, ACommandAcceptedBeforeARestartIsRefusedAfterItWithNoCounterFileNamed) {
  const auto dir = scratch("unnamed");
  std::vector<std::uint8_t> recorded;
  {
    ExecutiveHarness h("", true, dir.string());
    h.keep_dir();
    h.counter_file = "";
    h.uplink_extra = R"(,"counter_floor":0)";  // a new key: the operator says so once
    ASSERT_TRUE(h.boot().ok());
    h.counter = 41;
    const auto noop = h.make(FunctionCode::NOOP);
    recorded = h.packet(noop);
    EXPECT_EQ(final_reason(h, recorded, noop.counter), Reason::NONE);
  }
  const auto beside = dir / "key.hex.fsw-counter";
  ASSERT_TRUE(std::filesystem::exists(beside));
  struct stat st {};
  ASSERT_EQ(::stat(beside.c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 0777, 0600u);
  ExecutiveHarness h2("", true, dir.string());
  h2.counter_file = "";  // and no floor: the file beside the key is found
  ASSERT_TRUE(h2.boot().ok());
  EXPECT_EQ(h2.exec().command_counters().last_counter, 42u);
  EXPECT_EQ(final_reason(h2, recorded, 42), Reason::REPLAY);
}

TEST(UplinkReplay, AMissingOrCorruptCounterFileStopsTheStartUntilAFloorIsGiven) {
  {
    ExecutiveHarness h;
    h.counter_file = "";  // key.hex exists, key.hex.fsw-counter does not
    auto s = h.boot();
    ASSERT_FALSE(s.ok());
    EXPECT_NE(std::string(s.error().message).find("--counter-floor"), std::string::npos);
  }
  {
    ExecutiveHarness h;
    std::ofstream(h.dir() / "counter.txt") << "garbage\n";
    auto s = h.boot();
    ASSERT_FALSE(s.ok());
    EXPECT_NE(std::string(s.error().message).find("--counter-floor"), std::string::npos);
  }
  {
    ExecutiveHarness h;
    std::ofstream(h.dir() / "counter.txt") << "garbage\n";
    h.uplink_extra = R"(,"counter_floor":500)";
    ASSERT_TRUE(h.boot().ok());
    EXPECT_EQ(h.exec().command_counters().last_counter, 500u);
    h.counter = 499;
    const auto at_floor = h.make(FunctionCode::NOOP);  // 500: not above the floor
    EXPECT_EQ(final_reason(h, h.packet(at_floor), at_floor.counter), Reason::REPLAY);
    const auto above = h.make(FunctionCode::NOOP);  // 501
    EXPECT_EQ(final_reason(h, h.packet(above), above.counter), Reason::NONE);
  }
  {
    ExecutiveHarness h;  // a floor below the stored counter does not lower it
    std::ofstream(h.dir() / "counter.txt") << "0000000900\n";
    h.uplink_extra = R"(,"counter_floor":10)";
    ASSERT_TRUE(h.boot().ok());
    EXPECT_EQ(h.exec().command_counters().last_counter, 900u);
  }
}

TEST(UplinkReplay, AnExhaustedCounterIsRecoveredByANewKey) {
  const auto dir = scratch("exhausted");
  std::vector<std::uint8_t> old_safe;
  {
    ExecutiveHarness h("", true, dir.string());
    h.keep_dir();
    ASSERT_TRUE(h.boot().ok());
    h.counter = 0xFFFFFFFEu;
    const auto last = h.make(FunctionCode::NOOP);  // counter 0xFFFFFFFF: the last there is
    EXPECT_EQ(final_reason(h, h.packet(last), last.counter), Reason::NONE);
    cmd::SetModeArgs safe;
    safe.mode = static_cast<std::uint8_t>(Mode::SAFE);
    h.counter = 0xFFFFFFFEu;  // nothing above is left: every command is a replay
    const cmd::Command to_safe{FunctionCode::SET_MODE, 0xFFFFFFFFu, safe};
    old_safe = h.packet(to_safe);
    EXPECT_EQ(final_reason(h, old_safe, to_safe.counter), Reason::REPLAY);
  }
  {
    ExecutiveHarness h("", true, dir.string());  // a restart changes nothing
    h.keep_dir();
    ASSERT_TRUE(h.boot().ok());
    EXPECT_EQ(h.exec().command_counters().last_counter, 0xFFFFFFFFu);
  }
  ExecutiveHarness h("", true, dir.string());
  h.set_key(kNewKeyHex);  // `petra keygen --force`, the key installed onboard
  ASSERT_TRUE(h.boot().ok());
  EXPECT_EQ(h.exec().command_counters().last_counter, 0u);
  h.cycles(1);
  ASSERT_TRUE(h.has_event(static_cast<std::uint16_t>(EventId::UPLINK_NEW_KEY)));
  for (const auto& e : h.all<tlm::Event>()) {
    if (e.event_id == static_cast<std::uint16_t>(EventId::UPLINK_NEW_KEY)) {
      EXPECT_EQ(e.args[0], -1);  // the old key's 0xFFFFFFFF, as the event's i32
    }
  }
  h.counter = 0;
  const auto first = h.make(FunctionCode::NOOP);
  EXPECT_EQ(final_reason(h, h.packet(first), first.counter), Reason::NONE);
  // The old key's recorded commands do not verify any more.
  h.send_raw(old_safe);
  ASSERT_TRUE(h.cycle_until([&] { return h.has_ack(0, AckStage::REJECTED); }));
  EXPECT_EQ(h.acks_for(0).back().reason, static_cast<std::uint8_t>(Reason::BAD_AUTH));
  EXPECT_EQ(h.exec().mode(), Mode::IDLE);
}

}  // namespace
}  // namespace petra::test
