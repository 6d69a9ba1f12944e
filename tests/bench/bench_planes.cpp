// Disparity to ranked grind planes for ~25,000 points (issue target: <= 10 ms
// on one core, release). Input: the exact Q4 disparity of a ray-cast ridge
// rock seen by a Bumblebee2-like rig (tests/support/synthetic_disparity.hpp),
// with 0.1 px noise. Per-step CPU times are reported as counters (ms).
#include <benchmark/benchmark.h>

#include <time.h>
#include <cmath>
#include <vector>

#include "algo/chain/reconstruction.hpp"
#include "tests/support/synthetic_disparity.hpp"
#include "tests/support/test_rig.hpp"

namespace {

using namespace petra;

// Per-step times in this thread's CPU time (the machine is shared).
std::uint64_t thread_cpu_ns(void*) {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<std::uint64_t>(ts.tv_sec) * 1000000000ull +
         static_cast<std::uint64_t>(ts.tv_nsec);
}

struct Fixture {
  StereoRig rig = test::looking_rig(1);
  RectifiedPair pair = *rectify_geometry(rig, 1024, 768);
  test::SyntheticDisparity disp;
  ReconstructionBudget budget;
  std::vector<std::byte> block;

  explicit Fixture(long points) {
    const Rect box = test::rock_box(pair, test::ridge_rock(), 40, 30, 55, 0);
    // Grow the rock's box to `points` pixels around its centre (ground around it).
    const double aspect = static_cast<double>(box.w) / box.h;
    const int h = static_cast<int>(std::lround(std::sqrt(static_cast<double>(points) / aspect)));
    const int w = static_cast<int>(std::lround(static_cast<double>(points) / h));
    const Rect roi{box.x + box.w / 2 - w / 2, box.y + box.h / 2 - h / 2, w, h};
    disp = test::render_disparity(pair, roi, test::ridge_rock(), 0.1, 3);
    budget.max_roi_width = w;
    budget.max_roi_height = h;
    budget.max_points = static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
    block.resize(reconstruction_arena_bytes(budget));
  }
};

void BM_DisparityToPlanes(benchmark::State& state) {
  Fixture f(state.range(0));
  Arena arena(f.block);
  ReconstructionRequest req;
  req.planes = 3;
  StepClock clock{thread_cpu_ns, nullptr};
  double step_ns[StepTimings::kCapacity] = {};
  StepTimings last;
  std::size_t points = 0;
  int accepted = 0;
  for (auto _ : state) {
    arena.reset();
    StepTimings timings;
    auto r = reconstruct(f.rig, f.pair, f.disp.view(), req, ReconstructionParams{}, f.budget, arena,
                         clock, timings);
    if (!r) {
      state.SkipWithError(r.error().message);
      return;
    }
    points = r->stats.filtered_points > 0 ? static_cast<std::size_t>(r->stats.filtered_points) : 0;
    accepted = r->planes.accepted;
    for (std::size_t i = 0; i < timings.count; ++i)
      step_ns[i] += static_cast<double>(timings.steps[i].ns);
    last = timings;
    benchmark::DoNotOptimize(r);
  }
  state.counters["points"] = static_cast<double>(points);
  state.counters["planes"] = accepted;
  state.counters["arena_MB"] = static_cast<double>(f.block.size()) / 1e6;
  for (std::size_t i = 0; i < last.count; ++i)
    state.counters[std::string(last.steps[i].name) + "_ms"] =
        step_ns[i] / 1e6 / static_cast<double>(state.iterations());
}

}  // namespace

BENCHMARK(BM_DisparityToPlanes)->Arg(25000)->Unit(benchmark::kMillisecond)->MinTime(2.0);
BENCHMARK_MAIN();
