// The ground's telemetry archive (sim/ground/tlm_archive): storing a pass of
// 10,000 packets (decoding for the JSON column and SQLite inserts, committed
// in batches as the station does) and reading it back: counts per APID, every
// row, one APID over a time range. items_per_second = packets per second.
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <filesystem>
#include <string>

#include "sim/ground/tlm_archive.hpp"
#include "tests/sim/ground/archive_packets.hpp"

namespace {

using namespace petra;
namespace fs = std::filesystem;
constexpr int kPass = 10000;

std::string db_path() {
  return (fs::temp_directory_path() / ("petra_bench_archive_" + std::to_string(getpid()) + ".db"))
      .string();
}

void remove_db(const std::string& path) {
  for (const char* s : {"", "-wal", "-shm"}) fs::remove(path + s);
}

std::vector<std::vector<std::uint8_t>> pass() {
  std::vector<std::vector<std::uint8_t>> p;
  for (int k = 0; k < kPass; ++k) p.push_back(ground::testing::pass_packet(k));
  return p;
}

void BM_ArchiveInsertPass(benchmark::State& state) {
  const auto packets = pass();
  const std::string path = db_path();
  for (auto _ : state) {
    state.PauseTiming();
    remove_db(path);
    auto a = ground::TlmArchive::open(path);
    state.ResumeTiming();
    for (int k = 0; k < kPass; ++k) {
      const auto p = tlm::decode_tm(packets[static_cast<std::size_t>(k)]);
      (void)(*a)->add(packets[static_cast<std::size_t>(k)], *p, 2e9 + k * 0.01);
    }
    (void)(*a)->flush();
  }
  state.SetItemsProcessed(state.iterations() * kPass);
  remove_db(path);
}
BENCHMARK(BM_ArchiveInsertPass)->Unit(benchmark::kMillisecond);

// Fills an archive with one pass for the query benchmarks.
std::unique_ptr<ground::TlmArchive> filled(const std::string& path) {
  remove_db(path);
  auto a = ground::TlmArchive::open(path);
  const auto packets = pass();
  for (int k = 0; k < kPass; ++k)
    (void)(*a)->add(packets[static_cast<std::size_t>(k)],
                    *tlm::decode_tm(packets[static_cast<std::size_t>(k)]), 2e9 + k * 0.01);
  (void)(*a)->flush();
  return std::move(*a);
}

void BM_ArchiveCountPerApid(benchmark::State& state) {
  const std::string path = db_path();
  auto a = filled(path);
  for (auto _ : state) benchmark::DoNotOptimize(a->count_by_apid({}));
  remove_db(path);
}
BENCHMARK(BM_ArchiveCountPerApid)->Unit(benchmark::kMillisecond);

void BM_ArchiveReadWholePass(benchmark::State& state) {
  const std::string path = db_path();
  auto a = filled(path);
  for (auto _ : state) {
    long n = 0;
    (void)a->query({}, [&](const ground::ArchivedPacket&) { ++n; });
    benchmark::DoNotOptimize(n);
  }
  state.SetItemsProcessed(state.iterations() * kPass);
  remove_db(path);
}
BENCHMARK(BM_ArchiveReadWholePass)->Unit(benchmark::kMillisecond);

void BM_ArchiveEventsOverAMinute(benchmark::State& state) {
  const std::string path = db_path();
  auto a = filled(path);
  ground::ArchiveQuery q;
  q.apid = static_cast<int>(tlm::Apid::EVENT);
  q.from_s = 1020;
  q.to_s = 1080;
  for (auto _ : state) {
    long n = 0;
    (void)a->query(q, [&](const ground::ArchivedPacket&) { ++n; });
    benchmark::DoNotOptimize(n);
  }
  remove_db(path);
}
BENCHMARK(BM_ArchiveEventsOverAMinute)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
