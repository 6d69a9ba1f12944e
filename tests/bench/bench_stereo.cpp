// Stereo benchmark: accuracy and time of the edge-constrained DP matcher
// (algo/stereo/match_dp) against OpenCV StereoSGBM and StereoBM in the same run,
// on the eight Middlebury scenes of ../shared/data (bad-1 counters, strict
// and filled, nonocc and all, convention of sim/eval/middlebury.hpp), plus
// the speed targets of docs/performance.md:
//   BM_RectifyShadow_1024x768   rectify + shadow of a full 1024x768 pair
//   BM_MatchDp_Roi160 / BM_Sgbm_Roi160 / BM_StereoBM_Roi160
//                                160x160 ROI, 42 disparities, same ROI
// Run (one core):  taskset -c 1 build/release/tests/bench/bench_stereo
#include <benchmark/benchmark.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "algo/camera/rectify.hpp"
#include "algo/stereo/match_dp.hpp"
#include "algo/stereo/shadow.hpp"
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
  return petra::bench::middlebury_scene(name, "bench_stereo");
}

// Our matcher over a whole image: budget and arena sized at "init".
struct DpRunner {
  petra::MatchBudget budget;
  std::vector<std::byte> scratch;
  std::vector<std::int16_t> q4;

  DpRunner(int w, int h, int d) : budget{w, h, d}, scratch(petra::match_dp_scratch_bytes(budget)) {
    q4.resize(static_cast<std::size_t>(w) * h);
  }
  petra::DisparityMap run(petra::ConstGray8View l, petra::ConstGray8View r, petra::Rect roi,
                          int dmin, int dmax) {
    petra::Arena arena(scratch);
    petra::MatchDpParams p;
    p.disp_min = dmin;
    p.disp_max = dmax;
    petra::DisparityMap map{petra::ImageView<std::int16_t>(q4.data(), roi.w, roi.h), roi};
    petra::StereoInput in;
    in.left = l;
    in.right = r;
    auto s = petra::match_dp(in, roi, p, budget, arena, map);
    if (!s) {
      std::fprintf(stderr, "bench_stereo: %s\n", s.error().message);
      std::exit(1);
    }
    return map;
  }
};

void BM_MatchDp(benchmark::State& state, const char* name) {
  const MiddleburyData& d = scene(name);
  const int w = d.left.width, h = d.left.height;
  DpRunner runner(w, h, d.scene->disp_max + 1);
  petra::DisparityMap map;
  for (auto _ : state) {
    map = runner.run(d.left.view(), d.right.view(), {0, 0, w, h}, 0, d.scene->disp_max);
    benchmark::DoNotOptimize(map.q4.data());
  }
  petra::bench::report_bad1(state, petra::eval::to_float_image(map, w, h), d);
}

#ifdef PETRA_HAVE_OPENCV

// The peers: SGBM with the settings of shared/data/README.md
// (bench_middlebury.hpp), BM with OpenCV's usual settings.
cv::Ptr<cv::StereoMatcher> make_sgbm(int dmin, int ndisp) {
  return petra::bench::make_peer_sgbm(dmin, ndisp);
}
cv::Ptr<cv::StereoMatcher> make_bm(int dmin, int ndisp) {
  auto bm = cv::StereoBM::create(ndisp, 15);
  bm->setMinDisparity(dmin);
  bm->setUniquenessRatio(10);
  bm->setSpeckleWindowSize(100);
  bm->setSpeckleRange(32);
  return bm;
}

void BM_OpenCv(benchmark::State& state, const char* name, bool sgbm) {
  cv::setNumThreads(1);
  const MiddleburyData& d = scene(name);
  const int w = d.left.width, h = d.left.height;
  cv::Mat l(h, w, CV_8U, const_cast<std::uint8_t*>(d.left.pixels.data()));
  cv::Mat r(h, w, CV_8U, const_cast<std::uint8_t*>(d.right.pixels.data()));
  const int ndisp = (d.scene->disp_max + 1 + 15) / 16 * 16;
  auto m = sgbm ? make_sgbm(0, ndisp) : make_bm(0, ndisp);
  cv::Mat out;
  for (auto _ : state) {
    m->compute(l, r, out);
    benchmark::DoNotOptimize(out.data);
  }
  petra::bench::report_bad1(state, petra::bench::from_opencv(out, 0), d);
}

#endif

// --- speed targets -----------------------------------------------------------

// A Bumblebee2-like rig: 1024x768, 4.65 um pixels, 3.8 mm lens, 150 mm
// baseline, slightly converged, with radial distortion.
petra::StereoRig bumblebee_rig() {
  petra::StereoRig rig;
  for (int k = 0; k < 2; ++k) {
    petra::TsaiCamera& c = k == 0 ? rig.left : rig.right;
    c.width = 1024;
    c.height = 768;
    c.f_mm = 3.8;
    c.kappa1 = 0.02;
    c.sx = 1.0;
    c.cx_px = 511.5 + (k == 0 ? 3.0 : -2.0);
    c.cy_px = 383.5 + (k == 0 ? -1.5 : 2.0);
    c.dx_mm = c.dy_mm = 0.00465;
    const double yaw = (k == 0 ? 0.6 : -0.6) * M_PI / 180.0;
    c.R = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitY()).toRotationMatrix();
    c.T_mm = -(c.R * Eigen::Vector3d(k == 0 ? -75.0 : 75.0, 0.0, 0.0));
  }
  return rig;
}

// A textured 1024x768 image: the teddy pair tiled.
petra::io::GrayImage tiled(const petra::io::GrayImage& src, int w, int h) {
  petra::io::GrayImage out(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) out.view()(x, y) = src.view()(x % src.width, y % src.height);
  return out;
}

void BM_RectifyShadow_1024x768(benchmark::State& state) {
  const petra::StereoRig rig = bumblebee_rig();
  std::vector<petra::RemapEntry> tl(petra::Rectifier::table_entries(1024, 768)), tr(tl.size());
  auto rect = petra::Rectifier::create(rig, tl, tr);  // init, not timed
  if (!rect) {
    state.SkipWithError(rect.error().message);
    return;
  }
  const MiddleburyData& d = scene("teddy");
  const petra::io::GrayImage l = tiled(d.left, 1024, 768), r = tiled(d.right, 1024, 768);
  petra::io::GrayImage rl(1024, 768), rr(1024, 768), ml(1024, 768), mr(1024, 768);
  const petra::Rect all{0, 0, 1024, 768};
  for (auto _ : state) {
    auto s1 = rect->rectify(petra::StereoSide::left, l.view(), rl.view());
    auto s2 = rect->rectify(petra::StereoSide::right, r.view(), rr.view());
    auto t1 = petra::shadow_threshold(rl.view(), all, 0.1);
    auto t2 = petra::shadow_threshold(rr.view(), all, 0.1);
    if (!s1.ok() || !s2.ok() || !t1 || !t2) {
      state.SkipWithError("rectify/shadow failed");
      return;
    }
    auto n1 = petra::shadow_mask(rl.view(), all, t1->threshold, ml.view());
    auto n2 = petra::shadow_mask(rr.view(), all, t2->threshold, mr.view());
    benchmark::DoNotOptimize(n1);
    benchmark::DoNotOptimize(n2);
  }
}
BENCHMARK(BM_RectifyShadow_1024x768)->Unit(benchmark::kMillisecond);

// The 160x160 ROI with 42 disparities: teddy, around the teddy bear.
constexpr petra::Rect kRoi160{200, 120, 160, 160};
constexpr int kRoiDmin = 12, kRoiDmax = 53;

void BM_MatchDp_Roi160(benchmark::State& state) {
  const MiddleburyData& d = scene("teddy");
  DpRunner runner(kRoi160.w, kRoi160.h, kRoiDmax - kRoiDmin + 1);
  petra::DisparityMap map;
  for (auto _ : state) {
    map = runner.run(d.left.view(), d.right.view(), kRoi160, kRoiDmin, kRoiDmax);
    benchmark::DoNotOptimize(map.q4.data());
  }
}
BENCHMARK(BM_MatchDp_Roi160)->Unit(benchmark::kMillisecond);

#ifdef PETRA_HAVE_OPENCV
// The peers see the ROI widened on the left by their search range (they
// cannot match the ROI's first columns otherwise); 48 = 42 rounded up to 16.
void BM_OpenCv_Roi160(benchmark::State& state, bool sgbm) {
  cv::setNumThreads(1);
  const MiddleburyData& d = scene("teddy");
  const int margin = kRoiDmin + 48;
  const cv::Rect r(kRoi160.x - margin, kRoi160.y, kRoi160.w + margin, kRoi160.h);
  cv::Mat l = cv::Mat(d.left.height, d.left.width, CV_8U,
                      const_cast<std::uint8_t*>(d.left.pixels.data()))(r)
                  .clone();
  cv::Mat rr = cv::Mat(d.left.height, d.left.width, CV_8U,
                       const_cast<std::uint8_t*>(d.right.pixels.data()))(r)
                   .clone();
  auto m = sgbm ? make_sgbm(kRoiDmin, 48) : make_bm(kRoiDmin, 48);
  cv::Mat out;
  for (auto _ : state) {
    m->compute(l, rr, out);
    benchmark::DoNotOptimize(out.data);
  }
}
BENCHMARK_CAPTURE(BM_OpenCv_Roi160, Sgbm, true)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_OpenCv_Roi160, StereoBM, false)->Unit(benchmark::kMillisecond);
#endif

// --- Middlebury accuracy and time ----------------------------------------------

#define PETRA_SCENE(name) \
  BENCHMARK_CAPTURE(BM_MatchDp, name, #name)->Unit(benchmark::kMillisecond)->MinTime(0.5);
PETRA_SCENE(tsukuba)
PETRA_SCENE(venus)
PETRA_SCENE(sawtooth)
PETRA_SCENE(map)
PETRA_SCENE(teddy)
PETRA_SCENE(cones)
PETRA_SCENE(Aloe)
PETRA_SCENE(Baby1)
PETRA_SCENE(Rocks1)
#undef PETRA_SCENE

#ifdef PETRA_HAVE_OPENCV
#define PETRA_PEERS(name)                                     \
  BENCHMARK_CAPTURE(BM_OpenCv, Sgbm_##name, #name, true)      \
      ->Unit(benchmark::kMillisecond)                         \
      ->MinTime(0.5);                                         \
  BENCHMARK_CAPTURE(BM_OpenCv, StereoBM_##name, #name, false) \
      ->Unit(benchmark::kMillisecond)                         \
      ->MinTime(0.5);
PETRA_PEERS(tsukuba)
PETRA_PEERS(venus)
PETRA_PEERS(sawtooth)
PETRA_PEERS(map)
PETRA_PEERS(teddy)
PETRA_PEERS(cones)
PETRA_PEERS(Aloe)
PETRA_PEERS(Baby1)
PETRA_PEERS(Rocks1)
#undef PETRA_PEERS
#endif

}  // namespace

BENCHMARK_MAIN();
