// What the stereo benchmarks share (bench_stereo, bench_graphcut): the
// Middlebury scenes of ../shared/data loaded once per process, their bad-1
// figures as benchmark counters, and OpenCV's StereoSGBM with the peer's
// settings of shared/data/README.md, so that both reports compare against
// the same peer. PETRA_PERTURB_RIGHT="gain,offset,sigma[,seed[,vignetting]]"
// changes every right view as it is loaded (sim/eval/middlebury_perturb.hpp),
// e.g. PETRA_PERTURB_RIGHT=0.82,12,2 for the camera difference of
// docs/performance.md ("Camera differences").
#pragma once

#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstdlib>
#include <deque>
#include <limits>
#include <string>

#include "sim/eval/middlebury.hpp"
#include "sim/eval/middlebury_perturb.hpp"

#ifdef PETRA_HAVE_OPENCV
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>
#include <opencv2/core/utility.hpp>
#endif

namespace petra::bench {

// A scene of shared/data, loaded on first use; exits naming the problem when
// it cannot be read (a benchmark without its data has nothing to measure).
// A deque: references handed out stay valid as more scenes are loaded.
inline const eval::MiddleburyData& middlebury_scene(const std::string& name, const char* tool) {
  static std::deque<eval::MiddleburyData> cache;
  for (const auto& d : cache)
    if (name == d.scene->name) return d;
  const eval::MiddleburyScene* s = eval::find_middlebury_scene(name);
  if (s == nullptr) {
    std::fprintf(stderr, "%s: no Middlebury scene named %s\n", tool, name.c_str());
    std::exit(1);
  }
  auto d = eval::load_middlebury(*s, eval::default_data_root(PETRA_SOURCE_DIR));
  if (!d) {
    std::fprintf(stderr, "%s: %s\n", tool, d.error().message);
    std::exit(1);
  }
  if (const char* text = std::getenv("PETRA_PERTURB_RIGHT")) {
    auto p = eval::parse_perturbation(text);
    if (!p) {
      std::fprintf(stderr, "%s: PETRA_PERTURB_RIGHT: %s\n", tool, p.error().message);
      std::exit(1);
    }
    eval::perturb(d->right, *p);
  }
  cache.push_back(std::move(*d));
  return cache.back();
}

// bad-1 % (sim/eval/middlebury.hpp): strict and filled, nonocc and all, and
// filled on the published figures' terms (whole pixels, visible pixels).
inline void report_bad1(benchmark::State& state, const io::FloatImage& disp,
                        const eval::MiddleburyData& d) {
  auto s = eval::score_middlebury(disp.view(), d);
  if (!s) {
    state.SkipWithError(s.error().message);
    return;
  }
  state.counters["strict_nonocc"] = s->strict.nonocc;
  state.counters["strict_all"] = s->strict.all;
  state.counters["filled_nonocc"] = s->filled.nonocc;
  state.counters["filled_all"] = s->filled.all;
  state.counters["invalid_pct"] = s->invalid_pct;
  state.counters["filled_whole_visible"] = s->filled_whole_visible;
}

#ifdef PETRA_HAVE_OPENCV
// The peer of shared/data/README.md: blockSize 5, P1 200, P2 800,
// uniqueness 10, speckle window 100 px with range 2 (these reproduce the
// README's figures; callers set cv::setNumThreads(1)).
inline cv::Ptr<cv::StereoSGBM> make_peer_sgbm(int dmin, int ndisp) {
  return cv::StereoSGBM::create(dmin, ndisp, 5, 200, 800, 0, 0, 10, 100, 2);
}

// OpenCV's 1/16 px disparity as a float image, inf where it has none.
inline io::FloatImage from_opencv(const cv::Mat& d16, int dmin) {
  io::FloatImage out(d16.cols, d16.rows);
  for (int y = 0; y < d16.rows; ++y)
    for (int x = 0; x < d16.cols; ++x) {
      const short v = d16.at<short>(y, x);
      out.data[static_cast<std::size_t>(y) * d16.cols + x] =
          v < dmin * 16 ? std::numeric_limits<float>::infinity() : static_cast<float>(v) / 16.0f;
    }
  return out;
}
#endif

}  // namespace petra::bench
