// Open MCT's side of the station: the dictionary generated from the packet
// definitions, and history read back from the archive.
#include "sim/gnd/telemetry_history.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "sim/ground/tlm_archive.hpp"
#include "tests/sim/ground/archive_packets.hpp"

namespace petra::gnd {
namespace {

namespace fs = std::filesystem;

TEST(TelemetryHistory, DictionaryListsEveryFieldOfEveryPacketButProducts) {
  const std::string d = dictionary_json();
  for (const tlm::TmDesc& p : tlm::telemetry_table()) {
    const bool listed = d.find("\"name\":\"" + std::string(p.name) + "\"") != std::string::npos;
    EXPECT_EQ(listed, p.apid != static_cast<std::uint16_t>(tlm::Apid::PRODUCT)) << p.name;
  }
  EXPECT_NE(d.find("{\"key\":\"uptime_s\",\"unit\":\"s\""), std::string::npos) << d;
  EXPECT_NE(d.find("{\"key\":\"joint_deg[4]\""), std::string::npos);
}

TEST(TelemetryHistory, ReadsOnePointOrWholePacketsBackFromTheArchive) {
  const fs::path path =
      fs::temp_directory_path() / ("petra_history_" + std::to_string(getpid()) + ".db");
  {
    auto a = ground::TlmArchive::open(path.string());
    ASSERT_TRUE(a.ok());
    for (int k = 0; k < 120; ++k) {
      const auto raw = ground::testing::pass_packet(k);
      ASSERT_TRUE((*a)->add(raw, *tlm::decode_tm(raw), 2e9 + k).ok());
    }
  }
  HistoryRequest r{"HK", "uptime_s", 1000e3, 1000.5e3};  // packets 0..50, HK every 6th
  auto h = history_json(path.string(), r);
  ASSERT_TRUE(h.ok()) << h.error().message;
  EXPECT_EQ(h->rfind("[{\"t\":1000000.000,\"v\":0},{\"t\":1000060.000,\"v\":6},", 0), 0u) << *h;
  EXPECT_EQ(std::count(h->begin(), h->end(), '{'), 9);  // k = 0, 6, ..., 48
  r = {"EVENT", "", 0, 2e6, 3};                         // ERROR and FATAL events
  h = history_json(path.string(), r);
  ASSERT_TRUE(h.ok()) << h.error().message;
  EXPECT_NE(h->find("\"names\":{\"event\":"), std::string::npos) << *h;
  EXPECT_EQ(h->find("\"severity\":\"INFO\""), std::string::npos) << *h;
  r = {"HK", "no_such_field", 0, 2e6};
  EXPECT_FALSE(history_json(path.string(), r).ok());
  r = {"PRODUCT", "", 0, 2e6};
  EXPECT_FALSE(history_json(path.string(), r).ok());
  EXPECT_FALSE(history_json("", {"HK", "uptime_s", 0, 1}).ok());
  for (const char* s : {"", "-wal", "-shm"}) fs::remove(path.string() + s);
}

TEST(TelemetryHistory, GapsAreTheMissingSequenceCountsPerApid) {
  const fs::path path =
      fs::temp_directory_path() / ("petra_gaps_" + std::to_string(getpid()) + ".db");
  {
    auto a = ground::TlmArchive::open(path.string());
    ASSERT_TRUE(a.ok());
    // HK 0 1 2 _ _ 5 6, EVENT 0 1 _ 3 interleaved: one gap of 2 and one of 1.
    const std::pair<bool, std::uint16_t> sent[] = {{true, 0},  {false, 0}, {true, 1},  {true, 2},
                                                   {false, 1}, {true, 5},  {false, 3}, {true, 6}};
    std::uint32_t ms = 0;
    for (const auto& [is_hk, seq] : sent) {
      std::vector<std::uint8_t> raw(tlm::kMaxTmBytes);
      const tlm::TmTime t{1000u, (ms += 10) * 1000u};
      const auto flags = wire::SeqFlags::unsegmented;
      const std::size_t n = is_hk ? tlm::encode_tm(tlm::Housekeeping{}, seq, flags, t, raw)
                                  : tlm::encode_tm(tlm::Event{}, seq, flags, t, raw);
      raw.resize(n);
      ASSERT_TRUE((*a)->add(raw, *tlm::decode_tm(raw), 2e9).ok());
    }
  }
  auto g = gaps_json(path.string(), 0, 2e6);
  ASSERT_TRUE(g.ok()) << g.error().message;
  EXPECT_EQ(*g,
            "[{\"t\":1000060.000,\"packet\":\"HK\",\"apid\":16,\"seq\":5,\"missing\":2},"
            "{\"t\":1000070.000,\"packet\":\"EVENT\",\"apid\":17,\"seq\":3,\"missing\":1}]");
  g = gaps_json(path.string(), 1000065, 2e6);  // from EVENT 3 on: no predecessor, no gap
  ASSERT_TRUE(g.ok()) << g.error().message;
  EXPECT_EQ(*g, "[]");
  EXPECT_FALSE(gaps_json(path.string(), 2, 1).ok());
  EXPECT_FALSE(gaps_json("", 0, 1).ok());
  for (const char* s : {"", "-wal", "-shm"}) fs::remove(path.string() + s);
}

}  // namespace
}  // namespace petra::gnd
