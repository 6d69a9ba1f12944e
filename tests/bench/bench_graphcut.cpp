// Graph-cut matcher benchmarks (docs/performance.md, "Graph-cut stereo"):
//  - every Middlebury pair in ../shared/data, whole image, with bad-1 nonocc /
//    all, strict and filled, as counters, and OpenCV SGBM on the same pair in
//    the same run as the peer (blockSize 5, P1 200, P2 800, uniqueness 10,
//    speckle filter, one thread);
//  - the flight case: a 160x160 ROI with 42 disparities;
//  - time against ROI area and disparity count.
// Times are CPU time of the one thread (the machine is shared).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdio>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "algo/match_graphcut.hpp"
#include "tests/sim/eval/middlebury_local.hpp"

#if PETRA_HAVE_OPENCV
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>
#endif

namespace {

using petra::test::LoadedScene;
using petra::test::MiddleburyScene;

const LoadedScene& scene_data(const MiddleburyScene& s) {
  static std::map<std::string, LoadedScene> cache;
  auto it = cache.find(s.name);
  if (it == cache.end()) {
    LoadedScene sc;
    std::string err;
    if (!petra::test::load_scene(s, sc, err)) std::fprintf(stderr, "%s: %s\n", s.name.c_str(), err.c_str());
    it = cache.emplace(s.name, std::move(sc)).first;
  }
  return it->second;
}

// One matcher with its arena, sized for a budget.
struct Matcher {
  std::vector<std::byte> block;
  petra::Arena arena;
  petra::GraphCutMatcher m;
  explicit Matcher(const petra::GraphCutBudget& b)
      : block(petra::GraphCutMatcher::bytes_needed(b)), arena(block) {
    if (!m.init(arena, b).ok()) std::fprintf(stderr, "graphcut init failed\n");
  }
};

void set_bad1(benchmark::State& state, const petra::test::Bad1& b) {
  state.counters["strict_nonocc"] = b.strict_nonocc;
  state.counters["strict_all"] = b.strict_all;
  state.counters["filled_nonocc"] = b.filled_nonocc;
  state.counters["filled_all"] = b.filled_all;
}

void BM_GraphCut(benchmark::State& state, MiddleburyScene s) {
  const LoadedScene& sc = scene_data(s);
  const int w = sc.left.width, h = sc.left.height;
  Matcher mt({w, h, s.disp_max - s.disp_min + 1});
  std::vector<std::int16_t> q4(static_cast<std::size_t>(w) * h);
  petra::DisparityMap out{petra::ImageView<std::int16_t>(q4.data(), w, h), {}};
  petra::GraphCutParams p;
  p.disp_min = s.disp_min;
  p.disp_max = s.disp_max;
  petra::GraphCutReport report;
  for (auto _ : state) {
    auto r = mt.m.match(sc.left.view(), sc.right.view(), {0, 0, w, h}, p, out);
    if (!r) {
      state.SkipWithError(r.error().message);
      return;
    }
    report = *r;
  }
  set_bad1(state, petra::test::score_bad1(s, sc, out));
  state.counters["cycles"] = report.cycles;
  state.counters["expansions"] = report.expansions;
  state.counters["K"] = report.occlusion_k;
  state.counters["MB"] = static_cast<double>(mt.block.size()) / 1e6;
}

#if PETRA_HAVE_OPENCV
void BM_SGBM(benchmark::State& state, MiddleburyScene s) {
  cv::setNumThreads(1);
  const LoadedScene& sc = scene_data(s);
  const int w = sc.left.width, h = sc.left.height;
  const cv::Mat left(h, w, CV_8UC1, const_cast<std::uint8_t*>(sc.left.pixels.data()));
  const cv::Mat right(h, w, CV_8UC1, const_cast<std::uint8_t*>(sc.right.pixels.data()));
  const int count = (s.disp_max - s.disp_min + 1 + 15) / 16 * 16;
  auto sgbm = cv::StereoSGBM::create(s.disp_min, count, 5, 200, 800, 0, 0, 10, 100, 2,
                                     cv::StereoSGBM::MODE_SGBM);
  cv::Mat disp;
  for (auto _ : state) sgbm->compute(left, right, disp);
  // SGBM writes 16 x disparity too; below-range values mark invalid pixels.
  std::vector<std::int16_t> q4(static_cast<std::size_t>(w) * h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const std::int16_t v = disp.at<std::int16_t>(y, x);
      q4[static_cast<std::size_t>(y) * w + x] =
          v < s.disp_min * petra::kDisparityScale ? petra::kInvalidDisparity : v;
    }
  petra::ConstDisparityMap map(petra::ImageView<const std::int16_t>(q4.data(), w, h), {0, 0, w, h});
  set_bad1(state, petra::test::score_bad1(s, sc, map));
}
#endif

// The flight case and the scaling table: square ROIs centred on cones
// (textured, slanted surfaces), n disparities centred on the ROI's true
// disparities (the operator's range is set the same way from the scene).
void BM_GraphCutRoi(benchmark::State& state) {
  const MiddleburyScene s = petra::test::middlebury_scenes()[3];  // cones
  const LoadedScene& sc = scene_data(s);
  const int side = static_cast<int>(state.range(0));
  const int count = static_cast<int>(state.range(1));
  const petra::Rect roi{(sc.left.width - side) / 2, (sc.left.height - side) / 2, side, side};
  double lo = 1e9, hi = -1e9;
  for (int y = roi.y; y < roi.y + roi.h; ++y)
    for (int x = roi.x; x < roi.x + roi.w; ++x) {
      const int g = sc.gt_left.pixels[static_cast<std::size_t>(y) * sc.left.width + x];
      if (g == 0) continue;
      lo = std::min(lo, g / s.scale);
      hi = std::max(hi, g / s.scale);
    }
  Matcher mt({side, side, count});
  std::vector<std::int16_t> q4(static_cast<std::size_t>(side) * side);
  petra::DisparityMap out{petra::ImageView<std::int16_t>(q4.data(), side, side), {}};
  petra::GraphCutParams p;
  p.disp_min = std::max(0, static_cast<int>((lo + hi) / 2) - count / 2);
  p.disp_max = p.disp_min + count - 1;
  petra::GraphCutReport report;
  for (auto _ : state) {
    auto r = mt.m.match(sc.left.view(), sc.right.view(), roi, p, out);
    if (!r) {
      state.SkipWithError(r.error().message);
      return;
    }
    report = *r;
  }
  state.counters["cycles"] = report.cycles;
  state.counters["expansions"] = report.expansions;
  state.counters["disp_min"] = p.disp_min;
  state.counters["MB"] = static_cast<double>(mt.block.size()) / 1e6;
}

const bool registered = [] {
  for (const MiddleburyScene& s : petra::test::middlebury_scenes()) {
    benchmark::RegisterBenchmark(("GraphCut/" + s.name).c_str(), BM_GraphCut, s)
        ->Unit(benchmark::kMillisecond)
        ->MeasureProcessCPUTime()
        ->Iterations(1);
#if PETRA_HAVE_OPENCV
    benchmark::RegisterBenchmark(("SGBM/" + s.name).c_str(), BM_SGBM, s)
        ->Unit(benchmark::kMillisecond)
        ->MeasureProcessCPUTime();
#endif
  }
  benchmark::RegisterBenchmark("GraphCutRoi", BM_GraphCutRoi)
      ->Args({160, 42})
      ->Args({80, 42})
      ->Args({120, 42})
      ->Args({240, 42})
      ->Args({160, 21})
      ->Args({160, 84})
      ->Unit(benchmark::kMillisecond)
      ->MeasureProcessCPUTime();
  return true;
}();

}  // namespace

BENCHMARK_MAIN();
