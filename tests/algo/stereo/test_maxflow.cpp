#include "algo/stereo/maxflow.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <random>
#include <vector>

#include "tests/support/heap_counter.hpp"

namespace petra {
namespace {

using Capacity = std::int32_t;

struct Edge {
  int i, j;
  Capacity cap, rev;
};

struct SmallGraph {
  int n = 0;
  std::vector<Capacity> source, sink;
  std::vector<Edge> edges;
};

// Minimum s-t cut by enumerating every side assignment (bit k set = node k on
// the sink side): the independent oracle for the solver.
std::int64_t brute_force_min_cut(const SmallGraph& g) {
  std::int64_t best = INT64_MAX;
  for (std::uint32_t mask = 0; mask < (1u << g.n); ++mask) {
    std::int64_t cut = 0;
    for (int k = 0; k < g.n; ++k) {
      const bool in_sink = ((mask >> k) & 1u) != 0;
      cut += in_sink ? g.source[k] : g.sink[k];
    }
    for (const Edge& e : g.edges) {
      const bool si = ((mask >> e.i) & 1u) != 0;
      const bool sj = ((mask >> e.j) & 1u) != 0;
      if (!si && sj) cut += e.cap;
      if (si && !sj) cut += e.rev;
    }
    best = std::min(best, cut);
  }
  return best;
}

template <class Solver>
std::int64_t cut_of_solver_sides(const SmallGraph& g, const Solver& mf) {
  std::int64_t cut = 0;
  for (int k = 0; k < g.n; ++k) cut += mf.in_sink_side(k) ? g.source[k] : g.sink[k];
  for (const Edge& e : g.edges) {
    const bool si = mf.in_sink_side(e.i);
    const bool sj = mf.in_sink_side(e.j);
    if (!si && sj) cut += e.cap;
    if (si && !sj) cut += e.rev;
  }
  return cut;
}

SmallGraph random_graph(std::mt19937& rng, int n, int max_degree, int max_cap, bool with_infinite) {
  SmallGraph g;
  g.n = n;
  std::uniform_int_distribution<int> cap(0, max_cap);
  std::uniform_int_distribution<int> node(0, n - 1);
  std::uniform_int_distribution<int> coin(0, 3);
  for (int k = 0; k < n; ++k) {
    // Often only one terminal link, as in the graphs the matcher builds.
    const int c = coin(rng);
    g.source.push_back(c == 1 ? 0 : cap(rng));
    g.sink.push_back(c == 2 ? 0 : cap(rng));
  }
  std::vector<int> degree(n, 0);
  const int tries = n * max_degree;
  for (int t = 0; t < tries; ++t) {
    const int i = node(rng);
    const int j = node(rng);
    if (i == j || degree[i] >= max_degree || degree[j] >= max_degree) continue;
    ++degree[i];
    ++degree[j];
    Edge e{i, j, cap(rng), coin(rng) == 0 ? 0 : cap(rng)};
    if (with_infinite && coin(rng) == 0) {
      e.cap = MaxFlow<8>::kInfiniteCapacity;
      e.rev = 0;
    }
    g.edges.push_back(e);
  }
  return g;
}

template <class Solver>
void load(Solver& mf, const SmallGraph& g) {
  ASSERT_TRUE(mf.reset(g.n).ok());
  for (int k = 0; k < g.n; ++k) mf.add_terminal_weights(k, g.source[k], g.sink[k]);
  for (const Edge& e : g.edges) ASSERT_TRUE(mf.add_edge(e.i, e.j, e.cap, e.rev));
}

TEST(MaxFlow, EqualsBruteForceMinCutOnManyRandomGraphs) {
  StaticArena<1 << 16> storage;
  MaxFlow<8> mf;
  ASSERT_TRUE(mf.init(storage.arena(), 12).ok());
  std::mt19937 rng(12345);
  int checked = 0;
  for (int round = 0; round < 1200; ++round) {
    const int n = 1 + round % 12;
    const int max_cap = (round % 3 == 0) ? 3 : 100;  // small caps make many ties
    const SmallGraph g = random_graph(rng, n, 1 + round % 8, max_cap, round % 2 == 0);
    load(mf, g);
    const std::int64_t flow = mf.solve();
    const std::int64_t expected = brute_force_min_cut(g);
    ASSERT_EQ(flow, expected) << "round " << round << " n " << n;
    // The reported sides form a cut of exactly that cost.
    ASSERT_EQ(cut_of_solver_sides(g, mf), expected) << "round " << round;
    ++checked;
  }
  EXPECT_EQ(checked, 1200);
}

// Grid graphs with 4-neighbour edges, the shape the matcher builds; the value
// is checked against brute force on 3x4 grids.
TEST(MaxFlow, EqualsBruteForceOnGrids) {
  StaticArena<1 << 16> storage;
  MaxFlow<4> mf;
  ASSERT_TRUE(mf.init(storage.arena(), 12).ok());
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> cap(0, 50);
  for (int round = 0; round < 150; ++round) {
    SmallGraph g;
    g.n = 12;
    for (int k = 0; k < 12; ++k) {
      const int u = cap(rng) - 25;  // one signed unary, as an energy gives
      g.source.push_back(u > 0 ? u : 0);
      g.sink.push_back(u < 0 ? -u : 0);
    }
    for (int y = 0; y < 3; ++y)
      for (int x = 0; x < 4; ++x) {
        const int k = y * 4 + x;
        if (x + 1 < 4) g.edges.push_back({k, k + 1, cap(rng) / 5, cap(rng) / 5});
        if (y + 1 < 3) g.edges.push_back({k, k + 4, cap(rng) / 5, cap(rng) / 5});
      }
    load(mf, g);
    const std::int64_t expected = brute_force_min_cut(g);
    ASSERT_EQ(mf.solve(), expected) << "round " << round;
    ASSERT_EQ(cut_of_solver_sides(g, mf), expected);
  }
}

// The same check under every search policy: both trees always, one tree
// whenever the terminals are unbalanced, and one tree with an immediate
// fallback to both (orphan budget 0). Terminal links are skewed so one side
// is much smaller, as in the matcher's later expansions.
TEST(MaxFlow, EverySearchPolicyFindsTheMinimumCut) {
  StaticArena<1 << 16> storage;
  MaxFlow<6> mf;
  ASSERT_TRUE(mf.init(storage.arena(), 12).ok());
  std::mt19937 rng(4242);
  const int policies[3][2] = {{0, 2}, {1, 1000}, {1, 0}};
  for (int round = 0; round < 900; ++round) {
    const int n = 2 + round % 11;
    SmallGraph g = random_graph(rng, n, 1 + round % 6, 20, round % 3 == 0);
    // Keep a sink link on about one node in four (or source, every other round).
    for (int k = 0; k < n; ++k) {
      if (rng() % 4 != 0) (round % 2 == 0 ? g.sink : g.source)[k] = 0;
    }
    const std::int64_t expected = brute_force_min_cut(g);
    for (const auto& policy : policies) {
      mf.set_search_policy(policy[0], policy[1]);
      load(mf, g);
      ASSERT_EQ(mf.solve(), expected) << "round " << round << " policy " << policy[0];
      ASSERT_EQ(cut_of_solver_sides(g, mf), expected)
          << "round " << round << " policy " << policy[0];
    }
  }
}

TEST(MaxFlow, EmptyAndTerminalOnlyGraphs) {
  StaticArena<4096> storage;
  MaxFlow<2> mf;
  ASSERT_TRUE(mf.init(storage.arena(), 4).ok());
  ASSERT_TRUE(mf.reset(0).ok());
  EXPECT_EQ(mf.solve(), 0);
  // Terminal links only: each node passes min(source, sink).
  ASSERT_TRUE(mf.reset(3).ok());
  mf.add_terminal_weights(0, 5, 3);
  mf.add_terminal_weights(1, 0, 7);
  mf.add_terminal_weights(2, 4, 0);
  mf.add_terminal_weights(2, 0, 9);  // accumulates: source 4, sink 9
  EXPECT_EQ(mf.solve(), 3 + 0 + 4);
  EXPECT_FALSE(mf.in_sink_side(0));  // residual source link left
  EXPECT_TRUE(mf.in_sink_side(1));
  EXPECT_TRUE(mf.in_sink_side(2));
}

TEST(MaxFlow, ChainBottleneckAndInfiniteArcs) {
  StaticArena<4096> storage;
  MaxFlow<2> mf;
  ASSERT_TRUE(mf.init(storage.arena(), 4).ok());
  ASSERT_TRUE(mf.reset(4).ok());
  mf.add_terminal_weights(0, 100, 0);
  mf.add_terminal_weights(3, 0, 100);
  ASSERT_TRUE(mf.add_edge(0, 1, MaxFlow<2>::kInfiniteCapacity, 0));
  ASSERT_TRUE(mf.add_edge(1, 2, 6, 0));
  ASSERT_TRUE(mf.add_edge(2, 3, MaxFlow<2>::kInfiniteCapacity, 0));
  EXPECT_EQ(mf.solve(), 6);
  EXPECT_FALSE(mf.in_sink_side(1));
  EXPECT_TRUE(mf.in_sink_side(2));
}

TEST(MaxFlow, DegreeBudgetIsEnforcedWithoutChangingTheGraph) {
  StaticArena<4096> storage;
  MaxFlow<2> mf;
  ASSERT_TRUE(mf.init(storage.arena(), 4).ok());
  ASSERT_TRUE(mf.reset(4).ok());
  ASSERT_TRUE(mf.add_edge(0, 1, 1, 1));
  ASSERT_TRUE(mf.add_edge(0, 3, 1, 1));
  EXPECT_FALSE(mf.add_edge(0, 2, 1, 1));  // node 0 full
  EXPECT_EQ(mf.degree(0), 2);
  EXPECT_EQ(mf.degree(2), 0);
}

TEST(MaxFlow, InitAndResetRejectBadSizes) {
  StaticArena<256> small;
  MaxFlow<6> mf;
  EXPECT_EQ(mf.init(small.arena(), 0).code(), Errc::out_of_range);
  EXPECT_EQ(mf.init(small.arena(), 1 << 27).code(), Errc::out_of_range);
  EXPECT_EQ(mf.init(small.arena(), 1000).code(), Errc::capacity_exceeded);
  StaticArena<4096> storage;
  ASSERT_TRUE(mf.init(storage.arena(), 8).ok());
  EXPECT_EQ(mf.reset(9).code(), Errc::capacity_exceeded);
  EXPECT_LE(storage.arena().used(), MaxFlow<6>::bytes_needed(8));
}

TEST(MaxFlow, RepeatedSolvesAllocateNothingAndAgree) {
  std::vector<std::byte> block(MaxFlow<8>::bytes_needed(14));
  Arena arena(block);
  MaxFlow<8> mf;
  ASSERT_TRUE(mf.init(arena, 14).ok());
  std::mt19937 rng(99);
  std::vector<SmallGraph> graphs;
  for (int k = 0; k < 20; ++k) graphs.push_back(random_graph(rng, 14, 8, 40, true));
  std::vector<std::int64_t> flows;
  for (const SmallGraph& g : graphs) {
    load(mf, g);
    flows.push_back(mf.solve());
  }
  std::array<std::int64_t, 20> again{};
  {
    test::HeapScope scope;
    for (int k = 0; k < 20; ++k) {
      const SmallGraph& g = graphs[k];
      (void)mf.reset(g.n);
      for (int v = 0; v < g.n; ++v) mf.add_terminal_weights(v, g.source[v], g.sink[v]);
      for (const Edge& e : g.edges) (void)mf.add_edge(e.i, e.j, e.cap, e.rev);
      again[k] = mf.solve();
    }
    EXPECT_EQ(scope.allocations(), 0u);
  }
  for (int k = 0; k < 20; ++k) EXPECT_EQ(again[k], flows[k]);
}

}  // namespace
}  // namespace petra
