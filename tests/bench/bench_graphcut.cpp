// Graph-cut matcher benchmarks (docs/performance.md, "Graph-cut stereo"):
//  - every Middlebury pair of ../shared/data, whole image, bad-1 nonocc / all,
//    strict and filled as counters (sim/eval/middlebury.hpp), and OpenCV
//    SGBM on the same pair in the same run as the peer (blockSize 5, P1 200,
//    P2 800, uniqueness 10, speckle filter, one thread);
//  - the flight case, a 160x160 ROI with 42 disparities, and time against ROI
//    area and disparity count.
// Times: CPU time of the process (the machine is shared; wall time is not ours).
// Run (one core):  taskset -c 1 build/release/tests/bench/bench_graphcut
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <string>
#include <vector>

#include "algo/stereo/match_graphcut.hpp"
#include "algo/stereo/match_graphcut_bands.hpp"
#include "sim/eval/disparity_image.hpp"
#include "sim/eval/middlebury.hpp"
#include "tests/bench/bench_middlebury.hpp"

#ifdef PETRA_HAVE_OPENCV
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>
#include <opencv2/core/utility.hpp>
#endif

namespace {

using petra::eval::MiddleburyData;

const MiddleburyData& scene(const std::string& name) {
  return petra::bench::middlebury_scene(name, "bench_graphcut");
}

// Overrides of the defaults for the exploration commands of
// docs/graphcut.md ("Why one guided and one full cycle").
void apply_env_overrides(petra::GraphCutParams& p) {
  if (const char* c = std::getenv("PETRA_GC_CYCLES")) p.max_cycles = std::atoi(c);
  if (const char* c = std::getenv("PETRA_GC_START"))
    p.start = static_cast<petra::GraphCutStart>(std::atoi(c));
  if (const char* c = std::getenv("PETRA_GC_GUIDED")) p.guided_cycles = std::atoi(c);
  if (const char* c = std::getenv("PETRA_GC_RADIUS")) p.guided_radius = std::atoi(c);
  if (const char* c = std::getenv("PETRA_GC_NORMALISE")) {
    p.normalise_gray = std::atoi(c) != 0;
    p.dp_start.normalise_gray = p.normalise_gray;
  }
}

// One matcher with its arena, sized at "init" for a budget.
struct Matcher {
  std::vector<std::byte> block;
  petra::Arena arena;
  petra::GraphCutMatcher m;
  explicit Matcher(const petra::GraphCutBudget& b)
      : block(petra::GraphCutMatcher::bytes_needed(b)), arena(block) {
    if (!m.init(arena, b).ok()) {
      std::fprintf(stderr, "bench_graphcut: init failed\n");
      std::exit(1);
    }
  }
};

void BM_GraphCut(benchmark::State& state, const char* name) {
  const MiddleburyData& d = scene(name);
  const int w = d.left.width, h = d.left.height;
  // PETRA_GC_BAND_ROWS=N: in bands of N rows (+16 above and below), as petra-fsw does.
  const char* band_env = std::getenv("PETRA_GC_BAND_ROWS");
  const petra::GraphCutBands bands{band_env != nullptr ? std::atoi(band_env) : 0, 16};
  const petra::GraphCutBudget budget{w, h, d.scene->disp_max + 1};
  Matcher mt(budget);
  std::vector<std::byte> band_block(bands.rows > 0 ? petra::graph_cut_bands_bytes(budget, bands)
                                                   : 0);
  petra::Arena band_arena(band_block);
  std::vector<std::int16_t> q4(static_cast<std::size_t>(w) * h);
  petra::DisparityMap out{petra::ImageView<std::int16_t>(q4.data(), w, h), {}};
  petra::GraphCutParams p;
  p.disp_max = d.scene->disp_max;
  apply_env_overrides(p);
  const petra::StereoInput in{d.left.view(), d.right.view()};
  petra::GraphCutReport r;
  for (auto _ : state) {
    auto rep = bands.rows > 0
                   ? petra::match_graph_cut_bands(in, {0, 0, w, h}, p, bands, band_arena, out)
                   : mt.m.match(in, {0, 0, w, h}, p, out);
    if (!rep) {
      state.SkipWithError(rep.error().message);
      return;
    }
    r = *rep;
  }
  petra::bench::report_bad1(state, petra::eval::to_float_image(out, w, h), d);
  state.counters["cycles"] = r.cycles;
  state.counters["start"] = static_cast<int>(r.start);
  state.counters["expansions"] = r.expansions;
  state.counters["K"] = r.occlusion_k;
  state.counters["energy"] = static_cast<double>(r.energy);
  state.counters["nodes"] = static_cast<double>(r.graph_nodes);
  state.counters["MB"] =
      static_cast<double>(bands.rows > 0 ? band_block.size() : mt.block.size()) / 1e6;
}

#ifdef PETRA_HAVE_OPENCV
// The peer of shared/data/README.md (bench_middlebury.hpp).
void BM_Sgbm(benchmark::State& state, const char* name) {
  cv::setNumThreads(1);
  const MiddleburyData& d = scene(name);
  const int w = d.left.width, h = d.left.height;
  cv::Mat l(h, w, CV_8U, const_cast<std::uint8_t*>(d.left.pixels.data()));
  cv::Mat r(h, w, CV_8U, const_cast<std::uint8_t*>(d.right.pixels.data()));
  const int ndisp = (d.scene->disp_max + 1 + 15) / 16 * 16;
  auto sgbm = petra::bench::make_peer_sgbm(0, ndisp);
  cv::Mat out;
  for (auto _ : state) {
    sgbm->compute(l, r, out);
    benchmark::DoNotOptimize(out.data);
  }
  petra::bench::report_bad1(state, petra::bench::from_opencv(out, 0), d);
}
#endif

// The flight case and the scaling table: square ROIs centred on cones
// (textured, slanted surfaces), n disparities centred on the ROI's true
// disparities, as an operator sets the range from the scene.
void BM_GraphCutRoi(benchmark::State& state) {
  const MiddleburyData& d = scene("cones");
  const int side = static_cast<int>(state.range(0));
  const int count = static_cast<int>(state.range(1));
  const int w = d.left.width, h = d.left.height;
  const petra::Rect roi{(w - side) / 2, (h - side) / 2, side, side};
  double lo = 1e9, hi = -1e9;
  for (int y = roi.y; y < roi.y + roi.h; ++y)
    for (int x = roi.x; x < roi.x + roi.w; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * w + x;
      if (d.known[i] == 0) continue;
      lo = std::min(lo, static_cast<double>(d.gt.data[i]));
      hi = std::max(hi, static_cast<double>(d.gt.data[i]));
    }
  Matcher mt({side, side, count});
  std::vector<std::int16_t> q4(static_cast<std::size_t>(side) * side);
  petra::DisparityMap out{petra::ImageView<std::int16_t>(q4.data(), side, side), {}};
  petra::GraphCutParams p;
  p.disp_min = std::max(0, static_cast<int>((lo + hi) / 2) - count / 2);
  p.disp_max = p.disp_min + count - 1;
  apply_env_overrides(p);
  const petra::StereoInput in{d.left.view(), d.right.view()};
  petra::GraphCutReport r;
  for (auto _ : state) {
    auto rep = mt.m.match(in, roi, p, out);
    if (!rep) {
      state.SkipWithError(rep.error().message);
      return;
    }
    r = *rep;
  }
  state.counters["cycles"] = r.cycles;
  state.counters["start"] = static_cast<int>(r.start);
  state.counters["expansions"] = r.expansions;
  state.counters["disp_min"] = p.disp_min;
  state.counters["energy"] = static_cast<double>(r.energy);
  state.counters["nodes"] = static_cast<double>(r.graph_nodes);
  state.counters["MB"] = static_cast<double>(mt.block.size()) / 1e6;
}

void register_scene(const petra::eval::MiddleburyScene& s) {
  benchmark::RegisterBenchmark((std::string("GraphCut/") + s.name).c_str(), BM_GraphCut, s.name)
      ->Unit(benchmark::kMillisecond)
      ->MeasureProcessCPUTime()
      ->Iterations(1);
#ifdef PETRA_HAVE_OPENCV
  benchmark::RegisterBenchmark((std::string("Sgbm/") + s.name).c_str(), BM_Sgbm, s.name)
      ->Unit(benchmark::kMillisecond)
      ->MeasureProcessCPUTime();
#endif
}

const bool registered = [] {
  for (const auto& s : petra::eval::middlebury_scenes()) register_scene(s);
  for (const auto& s : petra::eval::real_rock_scenes()) register_scene(s);
  benchmark::RegisterBenchmark("GraphCutRoi", BM_GraphCutRoi)
      ->Args({160, 42})
      ->Args({80, 42})
      ->Args({120, 42})
      ->Args({240, 42})
      ->Args({320, 42})
      ->Args({160, 21})
      ->Args({160, 84})
      ->Unit(benchmark::kMillisecond)
      ->MeasureProcessCPUTime();
  return true;
}();

}  // namespace

BENCHMARK_MAIN();
