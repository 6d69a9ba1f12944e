#include "sim/ground/tlm_archive.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "tests/sim/ground/archive_packets.hpp"

namespace petra::ground {
namespace {

namespace fs = std::filesystem;

class TlmArchiveTest : public ::testing::Test {
 protected:
  void SetUp() override {
    path_ = fs::temp_directory_path() / ("petra_archive_" + std::to_string(getpid()) + ".db");
    remove_files();
  }
  void TearDown() override { remove_files(); }
  void remove_files() {
    for (const char* suffix : {"", "-wal", "-shm"}) fs::remove(path_.string() + suffix);
  }
  // Stores packets [first, last) of the synthetic pass, received at 2e9 + k s.
  void store(TlmArchive& a, int first, int last) {
    for (int k = first; k < last; ++k) {
      const auto raw = testing::pass_packet(k);
      auto p = tlm::decode_tm(raw);
      ASSERT_TRUE(p.ok()) << p.error().message;
      ASSERT_TRUE(a.add(raw, *p, 2e9 + k).ok());
    }
  }
  fs::path path_;
};

TEST_F(TlmArchiveTest, KeepsEveryPacketRawAndDecodedAcrossReopening) {
  {
    auto a = TlmArchive::open(path_.string());
    ASSERT_TRUE(a.ok()) << a.error().message;
    store(**a, 0, 600);
  }  // closed: committed
  auto a = TlmArchive::open(path_.string());
  ASSERT_TRUE(a.ok());
  store(**a, 600, 1200);
  auto counts = (*a)->count_by_apid({});
  ASSERT_TRUE(counts.ok());
  ASSERT_EQ(counts->size(), 6u);
  for (const auto& [apid, n] : *counts) EXPECT_EQ(n, 200) << "apid " << apid;

  int k = 0;
  ASSERT_TRUE((*a)->query({},
                          [&](const ArchivedPacket& p) {
                            EXPECT_EQ(p.raw, testing::pass_packet(k)) << k;  // byte for byte
                            EXPECT_DOUBLE_EQ(p.receive_s, 2e9 + k);
                            EXPECT_NEAR(p.scet_s, 1000 + k * 0.01, 1e-6);
                            EXPECT_EQ(p.decoded.find("{\"apid\":" + std::to_string(p.apid)), 0u);
                            ++k;
                          })
                  .ok());
  EXPECT_EQ(k, 1200);
}

TEST_F(TlmArchiveTest, QueriesByTimeApidAndSeverity) {
  auto a = TlmArchive::open(path_.string());
  ASSERT_TRUE(a.ok());
  store(**a, 0, 600);
  auto count = [&](const ArchiveQuery& q) {
    long n = 0;
    EXPECT_TRUE((*a)->query(q, [&](const ArchivedPacket&) { ++n; }).ok());
    return n;
  };
  ArchiveQuery q;
  q.from_s = 1001.0;  // spacecraft time: packets 100..199
  q.to_s = 1001.995;
  EXPECT_EQ(count(q), 100);
  q = {};
  q.by_receive_time = true;  // receive time: packets 10..19
  q.from_s = 2e9 + 10;
  q.to_s = 2e9 + 19;
  EXPECT_EQ(count(q), 10);
  q = {};
  q.apid = static_cast<int>(tlm::Apid::EVENT);
  EXPECT_EQ(count(q), 100);
  q.min_severity = 3;  // ERROR and FATAL: k % 5 in {3, 4} among k % 6 == 1
  EXPECT_EQ(count(q), 40);
  q = {};
  q.limit = 7;
  EXPECT_EQ(count(q), 7);
}

TEST_F(TlmArchiveTest, ExportsCsvWithAHeaderAndOneLinePerPacket) {
  auto a = TlmArchive::open(path_.string());
  ASSERT_TRUE(a.ok());
  store(**a, 0, 12);
  char* text = nullptr;
  std::size_t size = 0;
  std::FILE* f = open_memstream(&text, &size);
  ASSERT_TRUE((*a)->export_csv({}, f).ok());
  std::fclose(f);
  const std::string csv(text, size);
  std::free(text);
  EXPECT_EQ(csv.rfind("receive_s,scet_s,apid,packet,seq,severity,decoded\n", 0), 0u) << csv;
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 13);
  EXPECT_NE(csv.find(",17,EVENT,1,1,\"{\"\"apid\"\":17,"), std::string::npos) << csv;
}

TEST_F(TlmArchiveTest, AnUnopenableFileIsNamedWithTheReason) {
  auto a = TlmArchive::open("/nonexistent/dir/a.db");
  ASSERT_FALSE(a.ok());
  EXPECT_NE(std::string(a.error().message).find("/nonexistent/dir/a.db"), std::string::npos);
}

}  // namespace
}  // namespace petra::ground
