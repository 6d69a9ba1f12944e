// Rock proposals over a whole 1024 x 768 pair (algo/propose/proposer), as the
// flight service would run them: the flight job's chain sizing and
// parameters (FlightPipelineJob::sizing and pipeline_params of the parameter
// table's defaults: 512 x 384 ROIs, a 3-D point per 2 x 2 ROI pixels), reach
// from the stowed pose. Issue 26's target: <= 1 s CPU on one core.
//   BM_Propose/24, /26   realistic set entries 24 (one touching neighbour: 2
//                        rocks found) and 26 (4 rocks found, 2 offered)
//   BM_Detect/24, /26    the detection alone (whole pair at 1/4 resolution)
// Run (one core, from the repo root):
//   taskset -c 1 build/release/tests/bench/bench_propose --benchmark_repetitions=5
// The scenes are rendered once into build/release/test-cache (about 45 s CPU
// each), or read from PETRA_REAL_SET/scene_NN when set.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "algo/camera/calib_json.hpp"
#include "algo/propose/proposer.hpp"
#include "fsw/flight_pipeline_job.hpp"
#include "sim/io/image_io.hpp"
#include "tests/bench/bench_common.hpp"
#include "tests/support/cached_dir.hpp"

namespace {

using namespace petra;
namespace fs = std::filesystem;

using bench::thread_cpu_ns;

[[noreturn]] void die(const std::string& what) {
  bench::die("bench_propose", what);
}

template <class T>
T must(Result<T> r, const std::string& what) {
  return bench::must("bench_propose", std::move(r), what);
}

struct Pair {
  io::GrayImage left, right;
  StereoRig rig;
};

fs::path scene_dir(int index) {
  char name[32];
  std::snprintf(name, sizeof name, "scene_%02d", index);
  if (const char* set = std::getenv("PETRA_REAL_SET")) return fs::path(set) / name;
  const fs::path dir =
      test::cached_petra_output(std::string("real_") + name, PETRA_CLI_BIN,
                                "sim scene --real --set-index " + std::to_string(index));
  if (dir.empty()) die("rendering the realistic scene failed");
  return dir;
}

const Pair& scene(int index) {
  static std::map<int, Pair> pairs;
  auto it = pairs.find(index);
  if (it != pairs.end()) return it->second;
  const fs::path dir = scene_dir(index);
  Pair p;
  p.left = must(io::read_gray_image((dir / "left.pgm").string()), "left.pgm");
  p.right = must(io::read_gray_image((dir / "right.pgm").string()), "right.pgm");
  p.rig = must(parse_calib_json(must(io::read_text_file((dir / "calib.json").string()), "calib")),
               "calib.json");
  return pairs.emplace(index, std::move(p)).first->second;
}

// The proposer as the flight service would size it, in its own arena.
struct Flight {
  ProposerBudget budget;
  PipelineParams params;
  std::vector<std::byte> block;
  Arena arena;
  Proposer proposer;
};

std::unique_ptr<Flight> flight(const Pair& p) {
  fsw::JobBudget job;
  job.max_width = p.left.width;
  job.max_height = p.left.height;
  job.rig = &p.rig;
  const fsw::FlightPipelineJob::Sizing s = fsw::FlightPipelineJob::sizing(job);
  auto f = std::make_unique<Flight>();
  f->budget.pipeline = s.pipeline;
  f->budget.max_roi_width = s.roi_width;
  f->budget.max_roi_height = s.roi_height;
  f->params = fsw::FlightPipelineJob::pipeline_params(fsw::FlightPipelineJob::default_settings());
  f->block.resize(Proposer::arena_bytes(f->budget, f->params));
  f->arena = Arena(f->block);
  f->proposer = must(Proposer::create(p.rig, f->budget, f->params, arm::rover_arm_geometry(),
                                      arm::default_joint_limits(), f->arena),
                     "Proposer::create");
  return f;
}

void BM_Propose(benchmark::State& state) {
  const Pair& p = scene(static_cast<int>(state.range(0)));
  const std::unique_ptr<Flight> f = flight(p);
  const StepClock clock{thread_cpu_ns, nullptr};
  ProposalList last;
  for (auto _ : state) {
    auto r =
        f->proposer.run(p.left.view(), p.right.view(), ProposalRequest{}, arm::stow_pose(), clock);
    if (!r) {
      state.SkipWithError(r.error().message);
      return;
    }
    last = **r;
    benchmark::DoNotOptimize(last);
  }
  int offered = 0;
  for (int i = 0; i < last.count; ++i) offered += last.items[i].note == ProposalNote::ok ? 1 : 0;
  state.counters["candidates"] = last.candidates;
  state.counters["offered"] = offered;
  state.counters["arena_MiB"] = static_cast<double>(f->block.size()) / (1024.0 * 1024.0);
}

void BM_Detect(benchmark::State& state) {
  const Pair& p = scene(static_cast<int>(state.range(0)));
  const std::unique_ptr<Flight> f = flight(p);
  DetectionBudget db;
  db.image_width = p.left.width;
  db.image_height = p.left.height;
  db.factor = f->budget.detection_factor;
  for (auto _ : state) {
    auto d = detect_rocks(f->proposer.pipeline().rectifier(), p.left.view(), p.right.view(), {}, db,
                          DetectionParams{}, f->arena, {});
    if (!d) {
      state.SkipWithError(d.error().message);
      return;
    }
    benchmark::DoNotOptimize(*d);
    state.counters["rocks"] = d->count;
  }
  state.counters["detection_MiB"] =
      static_cast<double>(detection_arena_bytes(db)) / (1024.0 * 1024.0);
  state.counters["chain_run_MiB"] =
      static_cast<double>(Pipeline::run_bytes(f->budget.pipeline, f->params)) / (1024.0 * 1024.0);
}

}  // namespace

BENCHMARK(BM_Propose)
    ->Arg(24)
    ->Arg(26)
    ->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime()
    ->MinTime(2.0);
BENCHMARK(BM_Detect)
    ->Arg(24)
    ->Arg(26)
    ->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime()
    ->MinTime(2.0);
BENCHMARK_MAIN();
