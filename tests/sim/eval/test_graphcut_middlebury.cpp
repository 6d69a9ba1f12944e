// Graph-cut matcher on the Middlebury pairs, scored bad-1 on the project's
// convention (sim/eval/middlebury.hpp, ../shared/data/README.md).
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <limits>
#include <string>
#include <vector>

#include "algo/stereo/match_graphcut.hpp"
#include "sim/eval/disparity_image.hpp"
#include "sim/eval/middlebury.hpp"

namespace petra {
namespace {

double thread_cpu_s() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

struct MiddleburyOutcome {
  eval::MiddleburyScore score;
  GraphCutReport report;
  double cpu_s = 0;
};

// The labels and energy at the end of the guided cycles (the start's, if none).
struct GuidedEnd {
  std::vector<std::int16_t> labels;
  std::int64_t start_energy = 0;
  std::int64_t energy = 0;
};
void keep_last_guided(void* context, const GraphCutStep& step) {
  auto* g = static_cast<GuidedEnd*>(context);
  if (step.cycle >= 0 && !step.guided) return;
  if (step.cycle < 0) g->start_energy = step.energy_after;
  g->labels.assign(step.labels.begin(), step.labels.end());
  g->energy = step.energy_after;
}

// Whole image, budget sized for it (as `petra stereo --method gc` does).
MiddleburyOutcome run_scene(const eval::MiddleburyScene& s, const GraphCutParams& base) {
  MiddleburyOutcome o;
  auto data = eval::load_middlebury(s, eval::default_data_root(PETRA_SOURCE_DIR));
  EXPECT_TRUE(data.ok()) << (data ? "" : data.error().message);
  if (!data) return o;
  const int w = data->left.width, h = data->left.height;
  const GraphCutBudget budget{w, h, s.disp_max + 1};
  std::vector<std::byte> block(GraphCutMatcher::bytes_needed(budget));
  Arena arena(block);
  GraphCutMatcher m;
  EXPECT_TRUE(m.init(arena, budget).ok());
  std::vector<std::int16_t> q4(static_cast<std::size_t>(w) * h);
  DisparityMap out{ImageView<std::int16_t>(q4.data(), w, h), {}};
  GraphCutParams p = base;
  p.disp_min = 0;
  p.disp_max = s.disp_max;
  // PETRA_GC_START=3 (given): start from the ground truth (known pixels,
  // occluded ones included, made unique by the matcher), to see where the
  // energy takes it (docs/graphcut.md, "Limits").
  GuidedEnd guided;
  std::vector<std::int16_t> truth_q4(static_cast<std::size_t>(w) * h, kInvalidDisparity);
  if (p.start == GraphCutStart::given) {
    for (std::size_t i = 0; i < truth_q4.size(); ++i)
      if (data->known[i] != 0) truth_q4[i] = disparity_q4(data->gt.data[i]);
    p.start_map = ConstDisparityMap(ImageView<const std::int16_t>(truth_q4.data(), w, h), {});
    p.observer = {keep_last_guided, &guided};
  }
  const StereoInput in{data->left.view(), data->right.view()};
  const double t0 = thread_cpu_s();
  auto rep = m.match(in, {0, 0, w, h}, p, out);
  o.cpu_s = thread_cpu_s() - t0;
  EXPECT_TRUE(rep.ok()) << (rep ? "" : rep.error().message);
  if (!rep) return o;
  o.report = *rep;
  auto score = eval::score_middlebury(eval::to_float_image(out, w, h).view(), *data);
  EXPECT_TRUE(score.ok());
  if (score) o.score = *score;
  if (p.start == GraphCutStart::given) {
    io::FloatImage f(w, h, std::numeric_limits<float>::infinity());
    for (std::size_t i = 0; i < guided.labels.size(); ++i)
      if (guided.labels[i] >= 0) f.data[i] = static_cast<float>(guided.labels[i] + p.disp_min);
    auto at_start = eval::score_middlebury(f.view(), *data);
    std::printf(
        "%-8s from the truth: start E %lld; after the guided cycles E %lld, strict %.2f "
        "filled %.2f (nonocc)\n",
        s.name, static_cast<long long>(guided.start_energy), static_cast<long long>(guided.energy),
        at_start ? at_start->strict.nonocc : -1.0, at_start ? at_start->filled.nonocc : -1.0);
  }
  std::printf(
      "%-8s strict %5.2f / %5.2f  filled %5.2f / %5.2f (nonocc / all)  K %d l1 %d l2 %d  "
      "cycles %d expansions %d  E %lld  %.2f s cpu\n",
      s.name, o.score.strict.nonocc, o.score.strict.all, o.score.filled.nonocc, o.score.filled.all,
      o.report.occlusion_k, o.report.lambda1, o.report.lambda2, o.report.cycles,
      o.report.expansions, static_cast<long long>(o.report.energy), o.cpu_s);
  return o;
}

// Accuracy with the default parameters (seed 1). Where the matcher meets a
// target of the issue the bound is that target; where it does not, the bound
// is a regression guard just above the measured figure and the comment says
// so (docs/graphcut.md). The whole-image runs take a few seconds each: the
// matcher is compiled with -O2 even in Debug (algo/CMakeLists.txt); Aloe and
// Baby1 run in the benchmark (tests/bench/bench_graphcut.cpp).
struct Bound {
  const char* scene;
  double strict_nonocc, filled_nonocc, filled_all;
};
constexpr Bound kBounds[] = {
    // strict: reference 4.26; filled nonocc: SGBM 6.15; filled all: published 2.01.
    {"tsukuba", 4.26, 6.15, 2.01},
    // strict: reference 1.73; filled nonocc: OpenCV SGBM 1.22 (stricter than published 1.64).
    {"venus", 1.73, 1.22, 100},
    // strict: reference 13.06 not met (13.37): guard; filled nonocc: SGBM
    // 13.13 (published 11.2 and reference 12.50 not met: 12.72).
    {"teddy", 13.45, 13.13, 100},
    // strict: reference 7.57; filled nonocc: SGBM 6.20 and reference 6.32
    // (published 5.36 not met: 5.74).
    {"cones", 7.57, 6.20, 100},
    // No published or reference figures: SGBM of the same benchmark run.
    {"sawtooth", 6.41, 1.22, 100},
    {"map", 11.88, 1.01, 100},
};

TEST(GraphCutMiddlebury, Bad1WithinTargetsOrGuards) {
  for (const Bound& b : kBounds) {
    const eval::MiddleburyScene* s = eval::find_middlebury_scene(b.scene);
    ASSERT_NE(s, nullptr) << b.scene;
    const MiddleburyOutcome o = run_scene(*s, GraphCutParams{});
    EXPECT_LE(o.score.strict.nonocc, b.strict_nonocc) << b.scene;
    EXPECT_LE(o.score.filled.nonocc, b.filled_nonocc) << b.scene;
    EXPECT_LE(o.score.filled.all, b.filled_all) << b.scene;
    EXPECT_EQ(o.report.guided_cycles, 1) << b.scene;
    EXPECT_EQ(o.report.cycles, 1) << b.scene;
    EXPECT_EQ(o.report.start, GraphCutStart::dp) << b.scene;
  }
}

// PETRA_GC_TRACE=1: one line per expansion (labels changed, energy change, CPU ms).
struct Trace {
  std::vector<std::int16_t> previous;
  double t = 0;
};
void trace_step(void* context, const GraphCutStep& step) {
  auto* tr = static_cast<Trace*>(context);
  const double now = thread_cpu_s();
  long changed = 0;
  if (tr->previous.size() == step.labels.size()) {
    for (std::size_t i = 0; i < step.labels.size(); ++i)
      changed += tr->previous[i] != step.labels[i];
  }
  tr->previous.assign(step.labels.begin(), step.labels.end());
  std::printf("  cycle %d d %3d %s changed %7ld dE %9lld %7.1f ms\n", step.cycle, step.disparity,
              step.skipped ? "skip" : (step.applied ? "move" : "keep"), changed,
              static_cast<long long>(step.energy_after - step.energy_before), 1e3 * (now - tr->t));
  tr->t = thread_cpu_s();
}

// Exploration for tuning and the documentation, skipped unless asked:
//   PETRA_GC_SCENES=tsukuba,cones [PETRA_GC_CYCLES=n PETRA_GC_SEED=s
//   PETRA_GC_RANDOM=0|1 PETRA_GC_START=0|1|2|3 (occluded, block
//   matching, dp, given: the ground truth) PETRA_GC_GUIDED=n
//   PETRA_GC_RADIUS=r PETRA_GC_PRUNE=0|1 PETRA_GC_TRACE=1 (not with start 3)
//   PETRA_GC_K=k PETRA_GC_LAMBDA=l PETRA_GC_LAMBDA1=l1 PETRA_GC_LAMBDA2=l2
//   PETRA_GC_EDGE=t PETRA_GC_CLIP=c] <this test>
TEST(GraphCutMiddlebury, Explore) {
  const char* only = std::getenv("PETRA_GC_SCENES");
  if (only == nullptr) GTEST_SKIP();
  GraphCutParams p;
  if (const char* c = std::getenv("PETRA_GC_CYCLES")) p.max_cycles = std::atoi(c);
  if (const char* c = std::getenv("PETRA_GC_PRUNE")) p.prune = std::atoi(c) != 0;
  if (const char* c = std::getenv("PETRA_GC_START"))
    p.start = static_cast<GraphCutStart>(std::atoi(c));
  if (const char* c = std::getenv("PETRA_GC_RANDOM")) p.random_order = std::atoi(c) != 0;
  if (const char* c = std::getenv("PETRA_GC_GUIDED")) p.guided_cycles = std::atoi(c);
  if (const char* c = std::getenv("PETRA_GC_RADIUS")) p.guided_radius = std::atoi(c);
  if (const char* c = std::getenv("PETRA_GC_SEED"))
    p.seed = static_cast<std::uint32_t>(std::atoi(c));
  if (const char* c = std::getenv("PETRA_GC_K")) p.occlusion_k = std::atoi(c);
  if (const char* c = std::getenv("PETRA_GC_LAMBDA")) p.lambda = std::atoi(c);
  if (const char* c = std::getenv("PETRA_GC_LAMBDA1")) p.lambda1 = std::atoi(c);
  if (const char* c = std::getenv("PETRA_GC_LAMBDA2")) p.lambda2 = std::atoi(c);
  if (const char* c = std::getenv("PETRA_GC_EDGE")) p.edge_threshold = std::atoi(c);
  if (const char* c = std::getenv("PETRA_GC_CLIP")) p.data_clip = std::atoi(c);
  Trace trace;
  if (std::getenv("PETRA_GC_TRACE") != nullptr) p.observer = {trace_step, &trace};
  for (const eval::MiddleburyScene& s : eval::middlebury_scenes()) {
    if (std::string(only).find(s.name) == std::string::npos) continue;
    trace = Trace{};
    trace.t = thread_cpu_s();
    run_scene(s, p);
  }
}

}  // namespace
}  // namespace petra
