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
  std::printf("%-8s strict %5.2f / %5.2f  filled %5.2f / %5.2f (nonocc / all)  K %d l1 %d l2 %d  "
              "cycles %d exp %d skip %d  E %lld  nodes/exp %lld  %.3f s\n",
              s.name.c_str(), o.bad.strict_nonocc, o.bad.strict_all, o.bad.filled_nonocc,
              o.bad.filled_all, o.report.occlusion_k, o.report.lambda1, o.report.lambda2,
              o.report.cycles, o.report.expansions, o.report.expansions_skipped,
              static_cast<long long>(o.report.energy), static_cast<long long>(o.report.graph_nodes / std::max(1, o.report.expansions)), o.seconds);
  return o;
}

TEST(GraphCutMiddlebury, Explore) {
  const char* only = std::getenv("PETRA_GC_SCENES");
  if (only == nullptr) GTEST_SKIP();
  GraphCutParams p;
  if (const char* c = std::getenv("PETRA_GC_CYCLES")) p.max_cycles = std::atoi(c);
  if (const char* c = std::getenv("PETRA_GC_PRUNE")) p.prune = std::atoi(c) != 0;
  if (const char* c = std::getenv("PETRA_GC_BM")) p.block_matching_start = std::atoi(c) != 0;
  if (const char* c = std::getenv("PETRA_GC_RANDOM")) p.random_order = std::atoi(c) != 0;
  for (const auto& s : test::middlebury_scenes()) {
    if (std::string(only).find(s.name) == std::string::npos) continue;
    run_scene(s, p);
  }
}

}  // namespace
}  // namespace petra
