// Graph-cut matcher on the Middlebury pairs, scored bad-1 on the project's
// convention (../shared/data/README.md).
#include <gtest/gtest.h>

#include <chrono>
#include <ctime>
#include <cstdio>
#include <cstdlib>

#include "algo/match_graphcut.hpp"
#include "tests/sim/eval/middlebury_local.hpp"

namespace petra {
namespace {

double thread_cpu() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}
struct CycleClock {
  double start = 0, last = 0;
  int cycle = -1;
};
void on_step(void* ctx, const GraphCutStep& st) {
  auto& c = *static_cast<CycleClock*>(ctx);
  const double now = thread_cpu();
  if (st.cycle != c.cycle) {
    if (c.cycle >= 0) std::printf("  cycle %d: %.3f s\n", c.cycle, now - c.start);
    c.cycle = st.cycle;
    c.start = c.last;
  }
  c.last = now;
}

struct Outcome {
  test::Bad1 bad;
  GraphCutReport report;
  double seconds = 0;
};

Outcome run_scene(const test::MiddleburyScene& s, const GraphCutParams& base) {
  test::LoadedScene sc;
  std::string err;
  EXPECT_TRUE(test::load_scene(s, sc, err)) << err;
  const int w = sc.left.width, h = sc.left.height;
  GraphCutBudget budget{w, h, s.disp_max - s.disp_min + 1};
  std::vector<std::byte> block(GraphCutMatcher::bytes_needed(budget));
  Arena arena(block);
  GraphCutMatcher m;
  EXPECT_TRUE(m.init(arena, budget).ok());
  std::vector<std::int16_t> q4(w * h);
  DisparityMap out{ImageView<std::int16_t>(q4.data(), w, h), {}};
  GraphCutParams p = base;
  p.disp_min = s.disp_min;
  p.disp_max = s.disp_max;
  // Exploration knobs: K scaled (percent), lambda = K / divisor.
  const char* kmul = std::getenv("PETRA_GC_KMUL");
  const char* ldiv = std::getenv("PETRA_GC_LDIV");
  if (kmul != nullptr || ldiv != nullptr) {
    auto k = m.automatic_occlusion_k(sc.left.view(), sc.right.view(), {0, 0, w, h}, p);
    EXPECT_TRUE(k.ok());
    const int kk = *k * (kmul ? std::atoi(kmul) : 100) / 100;
    p.occlusion_k = kk;
    p.lambda = std::max(1, kk * 10 / (ldiv ? std::atoi(ldiv) : 50));
  }
  if (const char* t = std::getenv("PETRA_GC_THR")) p.edge_threshold = std::atoi(t);
  if (const char* c = std::getenv("PETRA_GC_CLIP")) p.data_clip = std::atoi(c);
  // CPU time of this thread: the machine is shared, wall time is not ours.
  auto cpu_now = [] {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
  };
  CycleClock clock;
  if (std::getenv("PETRA_GC_CYCLE_TIMES")) p.observer = {on_step, &clock};
  const double t0 = cpu_now();
  clock.start = clock.last = t0;
  auto rep = m.match(sc.left.view(), sc.right.view(), {0, 0, w, h}, p, out);
  const double t1 = cpu_now();
  Outcome o;
  EXPECT_TRUE(rep.ok()) << rep.error().message;
  if (!rep) return o;
  o.report = *rep;
  o.seconds = t1 - t0;
  o.bad = test::score_bad1(s, sc, out);
  if (const char* dump = std::getenv("PETRA_GC_DUMP")) {
    io::GrayImage img(w, h);
    for (int i = 0; i < w * h; ++i) {
      const int q = q4[i];
      img.pixels[i] = static_cast<std::uint8_t>(
          is_valid_disparity(static_cast<std::int16_t>(q)) ? 40 + 215 * (q / 16 - s.disp_min) / std::max(1, s.disp_max - s.disp_min) : 0);
    }
    (void)io::write_png(std::string(dump) + "/" + s.name + ".png", img.view());
    io::GrayImage gt(w, h);
    for (int i = 0; i < w * h; ++i) {
      const double g = sc.gt_left.pixels[i] / s.scale;
      gt.pixels[i] = static_cast<std::uint8_t>(sc.gt_left.pixels[i] == 0 ? 0 : 40 + 215 * (g - s.disp_min) / std::max(1, s.disp_max - s.disp_min));
    }
    (void)io::write_png(std::string(dump) + "/" + s.name + "_gt.png", gt.view());
  }
  std::printf("%-8s strict %5.2f / %5.2f  filled %5.2f / %5.2f (nonocc / all)  K %d l1 %d l2 %d  "
              "cycles %d exp %d skip %d  E %lld  nodes/exp %lld  %.3f s\n",
              s.name.c_str(), o.bad.strict_nonocc, o.bad.strict_all, o.bad.filled_nonocc,
              o.bad.filled_all, o.report.occlusion_k, o.report.lambda1, o.report.lambda2,
              o.report.cycles, o.report.expansions, o.report.expansions_skipped,
              static_cast<long long>(o.report.energy), static_cast<long long>(o.report.graph_nodes / std::max(1, o.report.expansions)), o.seconds);
  return o;
}

// Accuracy on the project's convention with the default parameters (seed 1).
// Where the matcher meets a target of the issue the bound is that target;
// where it does not, the bound is a regression guard just above the measured
// figure and the comment says so (docs/graphcut.md, docs/performance.md).
// The whole-image runs take a few seconds each: the matcher is compiled with
// -O2 even in Debug (algo/CMakeLists.txt); Aloe and Baby1 run in the benchmark.
struct Bound {
  const char* scene;
  double strict_nonocc, filled_nonocc, filled_all;
};
constexpr Bound kBounds[] = {
    // strict: reference 4.26 (not met, 4.28: guard); filled all: published 2.01.
    {"tsukuba", 4.40, 6.15, 2.01},
    // strict: reference 1.73; filled nonocc: OpenCV SGBM 1.22 (stricter than published 1.64).
    {"venus", 1.73, 1.22, 100},
    // strict: reference 13.06 (not met, 13.32: guard); filled nonocc: SGBM 13.13
    // (published 11.2 not met, 12.70).
    {"teddy", 13.50, 13.13, 100},
    // strict: reference 7.57; filled nonocc: published 5.36 and SGBM 6.20 not
    // met (6.28): guard.
    {"cones", 7.57, 6.45, 100},
    // No published or reference figures: SGBM from the same benchmark run.
    {"sawtooth", 6.41, 1.22, 100},
    {"map", 11.88, 1.01, 100},
};

TEST(GraphCutMiddlebury, Bad1WithinTargetsOrGuards) {
  for (const Bound& b : kBounds) {
    for (const auto& s : test::middlebury_scenes()) {
      if (s.name != b.scene) continue;
      const Outcome o = run_scene(s, GraphCutParams{});
      EXPECT_LE(o.bad.strict_nonocc, b.strict_nonocc) << s.name;
      EXPECT_LE(o.bad.filled_nonocc, b.filled_nonocc) << s.name;
      EXPECT_LE(o.bad.filled_all, b.filled_all) << s.name;
      EXPECT_EQ(o.report.cycles, 2) << s.name;
    }
  }
}

// Exploration for tuning and the documentation: PETRA_GC_SCENES=tsukuba,cones
// (and the PETRA_GC_* knobs above) prints figures; skipped otherwise.
TEST(GraphCutMiddlebury, Explore) {
  const char* only = std::getenv("PETRA_GC_SCENES");
  if (only == nullptr) GTEST_SKIP();
  GraphCutParams p;
  if (const char* c = std::getenv("PETRA_GC_CYCLES")) p.max_cycles = std::atoi(c);
  if (const char* c = std::getenv("PETRA_GC_PRUNE")) p.prune = std::atoi(c) != 0;
  if (const char* c = std::getenv("PETRA_GC_BM")) p.block_matching_start = std::atoi(c) != 0;
  if (const char* c = std::getenv("PETRA_GC_RANDOM")) p.random_order = std::atoi(c) != 0;
  if (const char* c = std::getenv("PETRA_GC_SEED")) p.seed = static_cast<std::uint32_t>(std::atoi(c));
  for (const auto& s : test::middlebury_scenes()) {
    if (std::string(only).find(s.name) == std::string::npos) continue;
    run_scene(s, p);
  }
}

}  // namespace
}  // namespace petra
