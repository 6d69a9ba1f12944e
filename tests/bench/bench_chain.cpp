// The whole onboard chain, stereo pair + ROI to ranked grind planes
// (Pipeline::run), as petra-fsw runs it: DP matcher, the flight parameters
// (FlightPipelineJob::pipeline_params of the parameter table's defaults) and
// the flight budget for a 512 x 384 ROI (FlightPipelineJob::sizing: the
// rectified bound of any such ROI, one 3-D point per 2 x 2 of it) and, as
// EVALUATE gives it, the arm's reach from the stowed pose (each face's
// footprint disc among those the arm reaches; PETRA_BENCH_NO_REACH=1: none,
// the chain as it was timed before 2026-12-07). Issue 21's
// target: <= 100 ms CPU on one core. Per-step CPU times (the pipeline's step
// clock) are counters in ms.
//   BM_Chain_RealScene   realistic simulated scene (`petra sim scene --real
//                        --set-index 0`), 512 x 384 ROI centred on the truth's ROI
//   BM_Chain_Rocks1      the Middlebury Rocks1 pair (../shared/data/real-rocks),
//                        512 x 384 ROI centred in the image, click on the grey rock
// Run (one core, from the repo root):
//   taskset -c 1 build/release/tests/bench/bench_chain --benchmark_repetitions=5
// The scene is rendered once into build/release/test-cache (about 40 s CPU), or
// read from PETRA_REAL_SET/scene_00 when set (a `petra sim set --real` dir).
#include <benchmark/benchmark.h>

#include <time.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "algo/camera/calib_json.hpp"
#include "algo/chain/pipeline.hpp"
#include "algo/propose/arm_reach.hpp"
#include "fsw/flight_pipeline_job.hpp"
#include "sim/io/image_io.hpp"
#include "sim/score/truth_file.hpp"
#include "tests/bench/bench_common.hpp"
#include "tests/support/cached_dir.hpp"

namespace {

using namespace petra;
namespace fs = std::filesystem;

constexpr int kRoiWidth = 512, kRoiHeight = 384;  // the flight default ROI budget
constexpr int kSceneIndex = 0;                    // realistic set entry: clear, blocky, 2 faces

using bench::thread_cpu_ns;

[[noreturn]] void die(const std::string& what) {
  bench::die("bench_chain", what);
}

template <class T>
T must(Result<T> r, const std::string& what) {
  return bench::must("bench_chain", std::move(r), what);
}

struct Case {
  io::GrayImage left, right;
  StereoRig rig;
  PipelineRequest request;
};

Rect centred_roi(int cx, int cy, int image_w, int image_h) {
  const int x = std::clamp(cx - kRoiWidth / 2, 0, image_w - kRoiWidth);
  const int y = std::clamp(cy - kRoiHeight / 2, 0, image_h - kRoiHeight);
  return {x, y, kRoiWidth, kRoiHeight};
}

Case load_pair(const fs::path& dir, const char* left, const char* right) {
  Case c;
  c.left = must(io::read_gray_image((dir / left).string()), (dir / left).string());
  c.right = must(io::read_gray_image((dir / right).string()), (dir / right).string());
  const std::string text = must(io::read_text_file((dir / "calib.json").string()), "calib.json");
  c.rig = must(parse_calib_json(text), "calib.json");
  return c;
}

fs::path scene_dir() {
  char name[32];
  std::snprintf(name, sizeof name, "scene_%02d", kSceneIndex);
  if (const char* set = std::getenv("PETRA_REAL_SET")) return fs::path(set) / name;
  const fs::path dir =
      test::cached_petra_output(std::string("real_") + name, PETRA_CLI_BIN,
                                "sim scene --real --set-index " + std::to_string(kSceneIndex));
  if (dir.empty()) die("rendering the realistic scene failed");
  return dir;
}

// The truth's ROI (rock, shadow, ground margin) and plane count, as
// toolchain/eval-scenes.sh gives them to `petra eval`; no click.
Case real_scene() {
  const fs::path dir = scene_dir();
  Case c = load_pair(dir, "left.pgm", "right.pgm");
  const std::string text = must(io::read_text_file((dir / "truth.json").string()), "truth.json");
  const sim::TruthFile truth = must(sim::parse_truth_json(text), "truth.json");
  const Rect& r = truth.roi;
  c.request.roi = centred_roi(r.x + r.w / 2, r.y + r.h / 2, c.left.width, c.left.height);
  c.request.planes = truth.planes;
  return c;
}

// Rocks stacked in a box, no ground: the rock is grown from the click
// (tests/sim/eval/test_rocks1_planes: the grey rock's click).
Case rocks1() {
  const fs::path dir = fs::path(PETRA_SOURCE_DIR) / "../shared/data/real-rocks/rocks1";
  Case c = load_pair(dir, "view1.png", "view5.png");
  c.request.roi = centred_roi(c.left.width / 2, c.left.height / 2, c.left.width, c.left.height);
  c.request.has_click = true;
  c.request.click_u = 420;
  c.request.click_v = 295;
  c.request.planes = 2;
  return c;
}

void run_chain(benchmark::State& state, const Case& c) {
  fsw::JobBudget job;
  job.max_width = c.left.width;
  job.max_height = c.left.height;
  job.rig = &c.rig;
  const PipelineBudget budget = fsw::FlightPipelineJob::sizing(job).pipeline;
  const PipelineParams params =
      fsw::FlightPipelineJob::pipeline_params(fsw::FlightPipelineJob::default_settings());
  std::vector<std::byte> block(Pipeline::arena_bytes(budget, params));
  Arena arena(block);
  auto pipeline = must(Pipeline::create(c.rig, budget, params, arena), "Pipeline::create");
  const ArmReach reach(arm::rover_arm_geometry(), arm::default_joint_limits(), arm::stow_pose(),
                       arm::kDefaultStandoffMm);
  PipelineRequest request = c.request;
  const char* no_reach = std::getenv("PETRA_BENCH_NO_REACH");
  request.reach = no_reach != nullptr && no_reach[0] == '1' ? nullptr : &reach;
  const StepClock clock{thread_cpu_ns, nullptr};
  double step_ns[StepTimings::kCapacity] = {};
  StepTimings last;
  PipelineOutput out;
  for (auto _ : state) {
    auto r = pipeline.run(c.left.view(), c.right.view(), request, clock);
    if (!r) {
      state.SkipWithError(r.error().message);
      return;
    }
    for (std::size_t i = 0; i < r->timings.count; ++i)
      step_ns[i] += static_cast<double>(r->timings.steps[i].ns);
    last = r->timings;
    out = *r;
    benchmark::DoNotOptimize(out);
  }
  const double n = static_cast<double>(state.iterations());
  state.counters["planes"] = out.result.planes.accepted;
  state.counters["points"] = static_cast<double>(out.result.stats.filtered_points);
  state.counters["stride"] = out.result.stats.point_stride;
  state.counters["budget_points"] = static_cast<double>(points_of(budget));
  state.counters["disp"] = out.range.max_px - out.range.min_px + 1;
  state.counters["reach"] = request.reach != nullptr ? 1 : 0;
  double total = 0;
  for (std::size_t i = 0; i < last.count; ++i) {
    state.counters[std::string(last.steps[i].name) + "_ms"] = step_ns[i] / 1e6 / n;
    total += step_ns[i];
  }
  state.counters["steps_ms"] = total / 1e6 / n;
}

void BM_Chain_RealScene(benchmark::State& state) {
  static const Case c = real_scene();
  run_chain(state, c);
}

void BM_Chain_Rocks1(benchmark::State& state) {
  static const Case c = rocks1();
  run_chain(state, c);
}

}  // namespace

BENCHMARK(BM_Chain_RealScene)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->MinTime(2.0);
BENCHMARK(BM_Chain_Rocks1)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->MinTime(2.0);
BENCHMARK_MAIN();
