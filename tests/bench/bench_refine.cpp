// Cost of the two refinements after matching (docs/performance.md):
//   BM_SubpixelDp_Roi160   window-SSD sub-pixel step (algo/stereo/disparity_subpixel)
//                          on the 160x160 ROI of teddy (the matchers' ROI
//                          benchmark), whole-pixel truth as the input map;
//                          args: window radius, search_px
//   BM_PlanePhotometric/N  photometric refinement of one grind plane
//                          (algo/surface/plane_photometric) over N face pixels of a
//                          steep, weakly textured synthetic face
// Run (one core):  taskset -c 1 build/release/tests/bench/bench_refine
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "algo/stereo/disparity_subpixel.hpp"
#include "algo/surface/plane_photometric.hpp"
#include "sim/eval/middlebury.hpp"

namespace {

constexpr petra::Rect kRoi160{200, 120, 160, 160};  // as bench_stereo's ROI benchmark

void BM_SubpixelDp_Roi160(benchmark::State& state) {
  auto d = petra::eval::load_middlebury(*petra::eval::find_middlebury_scene("teddy"),
                                        petra::eval::default_data_root(PETRA_SOURCE_DIR));
  if (!d) {
    std::fprintf(stderr, "bench_refine: %s\n", d.error().message);
    std::exit(1);
  }
  std::vector<std::int16_t> start(kRoi160.w * kRoi160.h, petra::kInvalidDisparity);
  for (int y = 0; y < kRoi160.h; ++y)
    for (int x = 0; x < kRoi160.w; ++x) {
      const float g = d->gt.view()(kRoi160.x + x, kRoi160.y + y);
      if (g > 0) start[y * kRoi160.w + x] = petra::disparity_q4(std::round(g));
    }
  petra::StereoInput in;
  in.left = d->left.view();
  in.right = d->right.view();
  const petra::SubpixelParams params{static_cast<int>(state.range(0)),
                                     static_cast<int>(state.range(1))};
  std::vector<std::int16_t> q4(start.size());
  long refined = 0;
  for (auto _ : state) {
    q4 = start;
    petra::DisparityMap map{petra::ImageView<std::int16_t>(q4.data(), kRoi160.w, kRoi160.h),
                            kRoi160};
    refined = *petra::refine_subpixel(in, params, map);
    benchmark::DoNotOptimize(q4.data());
  }
  state.counters["refined_px"] = static_cast<double>(refined);
}
BENCHMARK(BM_SubpixelDp_Roi160)->Args({2, 0})->Args({2, 2})->Unit(benchmark::kMillisecond);

// The face of test_plane_photometric: weak texture, slope -0.21 px/px in u.
constexpr int kW = 320, kH = 160;
const petra::DisparityPlane kTruth{-0.21, 0.02, 40.0, 160.0, 80.0};

double texture(double u, double v) {
  return 90 + 3.0 * std::sin(0.9 * u + 0.4 * v) + 2.0 * std::sin(0.37 * u - 0.8 * v + 1.0) +
         1.5 * std::cos(1.7 * u + 1.1 * v);
}

void BM_PlanePhotometric(benchmark::State& state) {
  std::vector<std::uint8_t> left(kW * kH), right(kW * kH);
  for (int v = 0; v < kH; ++v)
    for (int x = 0; x < kW; ++x) {
      left[v * kW + x] = static_cast<std::uint8_t>(std::lround(texture(x, v)));
      const double u =
          (x + kTruth.c - kTruth.a * kTruth.u0 + kTruth.b * (v - kTruth.v0)) / (1.0 - kTruth.a);
      right[v * kW + x] = static_cast<std::uint8_t>(std::lround(texture(u, v)));
    }
  // A square face of about N pixels around the plane's centre.
  const int side = static_cast<int>(std::sqrt(static_cast<double>(state.range(0))));
  std::vector<petra::PixelPos> px;
  for (int v = 80 - side / 2; v < 80 - side / 2 + side; ++v)
    for (int u = 160 - side / 2; u < 160 - side / 2 + side; ++u)
      px.push_back({static_cast<std::int16_t>(u), static_cast<std::int16_t>(v)});
  petra::DisparityPlane start = kTruth;
  start.a += 0.03;
  start.c += 0.3;
  const petra::ConstGray8View l(left.data(), kW, kH), r(right.data(), kW, kH);
  int iterations = 0;
  for (auto _ : state) {
    auto fit = petra::refine_plane_photometric(l, r, petra::Rect{0, 0, kW, kH}, px, start, {});
    iterations = fit->iterations;
    benchmark::DoNotOptimize(fit->plane.a);
  }
  state.counters["iterations"] = iterations;
  state.counters["pixels"] = static_cast<double>(px.size());
}
BENCHMARK(BM_PlanePhotometric)->Arg(625)->Arg(2500)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
