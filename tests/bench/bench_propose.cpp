// Rock proposals over a whole 1024 x 768 pair (algo/propose/proposer), as the
// flight service would run them: the flight job's chain sizing and
// parameters (FlightPipelineJob::sizing and pipeline_params of the parameter
// table's defaults: 512 x 384 ROIs, a 3-D point per 2 x 2 ROI pixels), reach
// from the stowed pose. Issue 26's target: <= 1 s CPU on one core.
//   BM_Propose/24, /26   realistic set entries 24 (one touching neighbour: 2
//                        rocks found) and 26 (4 rocks found, 2 offered)
//   BM_Detect/24, /26    the detection alone (whole pair at 1/4 resolution)
//   BM_TableBuild        the chain's remap tables at the flight sizing
//                        (Pipeline::create): what a rebuild of the chain costs
//   BM_FlightTurns/24    the flight job (FlightPipelineJob::run) taking turns:
//                        EVALUATE of rank 1's ROI, then PROPOSE of the whole
//                        pair; the runner's release before each, as petra-fsw
// Run (one core, from the repo root):
//   taskset -c 1 build/release/tests/bench/bench_propose --benchmark_repetitions=5
// The scenes are rendered once into build/release/test-cache (about 45 s CPU
// each), or read from PETRA_REAL_SET/scene_NN when set.
#include <benchmark/benchmark.h>

#include <atomic>
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

// The chain and its proposer as the flight service would size them, in
// their own arena (not moved: the proposer points to the pipeline).
struct Flight {
  ProposerBudget budget;
  PipelineParams params;
  std::vector<std::byte> block;
  Arena arena;
  Pipeline pipeline;
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
  f->pipeline =
      must(Pipeline::create(p.rig, f->budget.pipeline, f->params, f->arena), "Pipeline::create");
  f->proposer = must(Proposer::create(f->pipeline, f->budget, arm::rover_arm_geometry(),
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
    auto d = detect_rocks(f->pipeline.rectifier(), p.left.view(), p.right.view(), {}, db,
                          DetectionParams{}, f->arena, {});
    if (!d) {
      state.SkipWithError(d.error().message);
      return;
    }
    benchmark::DoNotOptimize(*d);
    state.counters["rocks"] = d->count;
  }
  state.counters["detection_MiB"] =
      static_cast<double>(Proposer::detection_bytes(f->budget)) / (1024.0 * 1024.0);
  state.counters["chain_run_MiB"] =
      static_cast<double>(Pipeline::run_bytes(f->budget.pipeline, f->params)) / (1024.0 * 1024.0);
}

void BM_TableBuild(benchmark::State& state) {
  const Pair& p = scene(24);
  const std::unique_ptr<Flight> f = flight(p);
  std::vector<std::byte> block(Pipeline::arena_bytes(f->budget.pipeline, f->params));
  Arena arena(block);
  for (auto _ : state) {
    arena.release_to(0);
    auto pipeline = Pipeline::create(p.rig, f->budget.pipeline, f->params, arena);
    if (!pipeline) {
      state.SkipWithError(pipeline.error().message);
      return;
    }
    benchmark::DoNotOptimize(pipeline->rectifier());
  }
  state.counters["tables_MiB"] =
      static_cast<double>(Pipeline::init_bytes(f->budget.pipeline)) / (1024.0 * 1024.0);
}

// A flight job's request on the pair with the parameter table's defaults:
// PROPOSE of the whole pair from the stowed pose.
fsw::EvalRequest propose_request(const Pair& p) {
  fsw::EvalRequest r;
  r.kind = fsw::JobKind::PROPOSE;
  r.left = p.left.view();
  r.right = p.right.view();
  r.rig = &p.rig;
  const fsw::FlightPipelineJob::Settings s = fsw::FlightPipelineJob::default_settings();
  r.shadow_fraction = s.shadow_fraction;
  r.disp_min_px = s.disp_min_px;
  r.disp_max_px = s.disp_max_px;
  r.arm_pose = arm::stow_pose();
  return r;
}

// EVALUATE of a proposal's ROI, click and c (SELECT_PROPOSAL then EVALUATE).
fsw::EvalRequest evaluate_request(const fsw::EvalRequest& propose, const RockProposal& best) {
  fsw::EvalRequest r = propose;
  r.kind = fsw::JobKind::EVALUATE;
  r.selection.roi = best.rock.roi;
  r.selection.has_click = true;
  r.selection.click_u = best.rock.click_u;
  r.selection.click_v = best.rock.click_v;
  r.selection.planes = best.planes_c;
  return r;
}

void BM_FlightTurns(benchmark::State& state) {
  const Pair& p = scene(static_cast<int>(state.range(0)));
  hal::SystemClock clock;
  fsw::FlightPipelineJob job(clock);
  fsw::JobBudget budget{p.left.width, p.left.height, 8192};
  budget.rig = &p.rig;
  std::vector<std::byte> block(job.arena_bytes(budget));
  Arena arena(block);
  if (!job.init(budget, &p.rig, arena).ok()) return state.SkipWithError("init");
  const std::size_t after_init = arena.mark();
  const std::atomic<bool> cancel{false};
  auto turn = [&](const fsw::EvalRequest& r, fsw::EvalOutput& out) {
    arena.release_to(after_init);  // what the runner does before each run
    return job.run(r, arena, cancel, out).ok();
  };
  const fsw::EvalRequest propose = propose_request(p);
  fsw::EvalOutput listed;
  if (!turn(propose, listed) || listed.proposals == nullptr || listed.proposals->count == 0)
    return state.SkipWithError("no proposal to evaluate");
  const fsw::EvalRequest evaluate = evaluate_request(propose, listed.proposals->items[0]);
  for (auto _ : state) {
    fsw::EvalOutput e, q;
    if (!turn(evaluate, e) || !turn(propose, q)) return state.SkipWithError("a turn failed");
    benchmark::DoNotOptimize(q.proposals);
  }
  state.counters["arena_MiB"] = static_cast<double>(block.size()) / (1024.0 * 1024.0);
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
BENCHMARK(BM_TableBuild)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->MinTime(2.0);
BENCHMARK(BM_FlightTurns)
    ->Arg(24)
    ->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime()
    ->MinTime(4.0);
BENCHMARK_MAIN();
