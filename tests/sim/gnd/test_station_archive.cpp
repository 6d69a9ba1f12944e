// The station's archive over a pass (issue 25's target): 10,000 telemetry
// packets sent over UDP to `petra gnd serve`'s station, the station stopped
// and started again half way on the same archive file; every packet is then
// in the archive (counts per APID equal to those sent), raw bytes included.
// Prints the insert and query figures (docs/ops.md); asserts none.
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <thread>

#include "hal/udp_link.hpp"
#include "sim/gnd/ground_station.hpp"
#include "sim/ground/tlm_archive.hpp"
#include "tests/sim/ground/archive_packets.hpp"

namespace petra::gnd {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

constexpr int kPass = 10000;

// Sends packets [first, last) at a pace a loaded machine's receiver keeps up
// with, then waits until the station has counted them all.
void send_pass(GroundStation& station, std::uint16_t port, int first, int last,
               std::map<int, long>& sent) {
  hal::UdpLink link;
  ASSERT_TRUE(link.open("127.0.0.1", 0).ok());
  ASSERT_TRUE(link.set_peer("127.0.0.1", port).ok());
  const std::uint64_t before = station.packets();
  for (int k = first; k < last; ++k) {
    const auto raw = ground::testing::pass_packet(k);
    ASSERT_EQ(link.send(raw), hal::SendResult::sent);
    ++sent[(raw[0] & 0x07) << 8 | raw[1]];
    if (k % 50 == 49) std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  const auto deadline = Clock::now() + std::chrono::seconds(60);
  while (station.packets() - before < static_cast<std::uint64_t>(last - first) &&
         Clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  EXPECT_EQ(station.packets() - before, static_cast<std::uint64_t>(last - first))
      << "packets lost on loopback before the station (not the archive)";
}

TEST(StationArchive, APassOf10000PacketsSurvivesARestartComplete) {
  const fs::path dir =
      fs::temp_directory_path() / ("petra_station_archive_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "petra.key") << std::string(64, 'a') << "\n";
  std::uint16_t port = 0;
  {
    hal::UdpLink probe;  // a free port for both runs of the station
    ASSERT_TRUE(probe.open("127.0.0.1", 0).ok());
    port = probe.local_port();
  }
  StationOptions options;
  options.key_path = (dir / "petra.key").string();
  options.tlm_port = port;
  options.archive_path = (dir / "pass.db").string();

  std::map<int, long> sent;
  double insert_s = 0;
  for (const auto& [first, last] : {std::pair{0, kPass / 2}, std::pair{kPass / 2, kPass}}) {
    GroundStation station;
    ASSERT_TRUE(station.start(options).ok());
    const auto t0 = Clock::now();
    send_pass(station, port, first, last, sent);
    station.stop();  // commits; the next run opens the same file
    insert_s += std::chrono::duration<double>(Clock::now() - t0).count();
    EXPECT_EQ(station.archive_errors(), 0u);
  }

  auto archive = ground::TlmArchive::open(options.archive_path);
  ASSERT_TRUE(archive.ok()) << archive.error().message;
  const auto t0 = Clock::now();
  auto counts = (*archive)->count_by_apid({});
  const double count_ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
  ASSERT_TRUE(counts.ok()) << counts.error().message;
  EXPECT_EQ(*counts, sent);
  long total = 0;
  for (const auto& [apid, n] : *counts) total += n;
  EXPECT_EQ(total, kPass);

  const auto t1 = Clock::now();
  long rows = 0, same = 0;
  ASSERT_TRUE((*archive)
                  ->query({},
                          [&](const ground::ArchivedPacket& p) {
                            same += p.raw == ground::testing::pass_packet(static_cast<int>(rows));
                            ++rows;
                          })
                  .ok());
  const double query_ms = std::chrono::duration<double, std::milli>(Clock::now() - t1).count();
  EXPECT_EQ(rows, kPass);
  EXPECT_EQ(same, kPass) << "raw bytes as received, in receive order";
  std::printf(
      "archive: %d packets stored in %.2f s of sending (paced), counted per APID in "
      "%.1f ms, all read back in %.1f ms\n",
      kPass, insert_s, count_ms, query_ms);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace petra::gnd
