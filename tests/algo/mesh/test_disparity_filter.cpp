#include "algo/mesh/disparity_filter.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "tests/support/heap_counter.hpp"

namespace petra {
namespace {

struct Map {
  int w, h;
  std::vector<std::int16_t> q;
  Map(int w_, int h_) : w(w_), h(h_), q(static_cast<std::size_t>(w_) * h_, kInvalidDisparity) {}
  DisparityMap view() { return {ImageView<std::int16_t>(q.data(), w, h), Rect{10, 20, w, h}}; }
  std::int16_t& at(int x, int y) { return q[static_cast<std::size_t>(y) * w + x]; }
};

// Straight from the definition: neighbours' mean, compared in pixels.
bool keep_reference(Map& m, int x, int y, const MeanFilterParams& p) {
  const int r = p.window / 2;
  double sum = 0;
  int n = 0;
  for (int yy = y - r; yy <= y + r; ++yy)
    for (int xx = x - r; xx <= x + r; ++xx) {
      if (xx < 0 || yy < 0 || xx >= m.w || yy >= m.h || (xx == x && yy == y)) continue;
      if (!is_valid_disparity(m.at(xx, yy))) continue;
      sum += disparity_px(m.at(xx, yy));
      ++n;
    }
  if (n == 0 || n < p.min_support) return false;
  return std::abs(disparity_px(m.at(x, y)) - sum / n) <= p.tolerance_px + 1e-9;
}

TEST(DisparityFilter, RemovesSpikesAndIsolatedPixelsKeepsSmoothSurfaces) {
  Map m(60, 40);
  for (int y = 0; y < 40; ++y)
    for (int x = 0; x < 60; ++x)
      m.at(x, y) = disparity_q4(20.0 + 0.1 * x + 0.05 * y);      // a tilted plane
  m.at(30, 20) = disparity_q4(35.0);                             // spike
  m.at(10, 10) = disparity_q4(5.0);                              // spike
  for (int y = 0; y < 40; ++y) m.at(50, y) = kInvalidDisparity;  // a column hole is harmless
  // An isolated pixel in an invalid patch.
  for (int y = 30; y < 39; ++y)
    for (int x = 2; x < 11; ++x) m.at(x, y) = kInvalidDisparity;
  m.at(6, 34) = disparity_q4(21.0);

  Map out(60, 40);
  StaticArena<4096> arena;
  MeanFilterParams p;  // 5x5, 1 px, 3 neighbours
  auto stats = mean_filter_disparity(m.view(), out.view(), p, arena.arena());
  ASSERT_TRUE(stats.ok()) << stats.error().message;
  const long valid_in = 60 * 40 - 40 - 81 + 1;
  EXPECT_EQ(stats->before, valid_in);
  EXPECT_EQ(stats->removed_spikes, 2);
  EXPECT_EQ(stats->removed_isolated, 1);
  EXPECT_EQ(stats->after, valid_in - 3);
  EXPECT_FALSE(is_valid_disparity(out.at(30, 20)));
  EXPECT_FALSE(is_valid_disparity(out.at(10, 10)));
  EXPECT_FALSE(is_valid_disparity(out.at(6, 34)));
  EXPECT_EQ(out.at(31, 20), m.at(31, 20));
  EXPECT_EQ(count_valid(out.view()), stats->after);
  EXPECT_EQ(out.view().roi, m.view().roi);
  EXPECT_EQ(arena.arena().used(), 0u);  // scratch released
}

TEST(DisparityFilter, MatchesTheDefinitionOnRandomMaps) {
  std::mt19937 rng(5);
  for (int trial = 0; trial < 20; ++trial) {
    const int w = 7 + static_cast<int>(rng() % 40), h = 5 + static_cast<int>(rng() % 30);
    Map m(w, h), out(w, h);
    std::uniform_real_distribution<double> noise(-1.5, 1.5);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        if (rng() % 5 != 0) m.at(x, y) = disparity_q4(-10.0 + 0.2 * x + noise(rng));
    MeanFilterParams p;
    p.window = 3 + 2 * static_cast<int>(rng() % 4);
    p.tolerance_px = 0.5 + 0.25 * static_cast<int>(rng() % 4);
    p.min_support = static_cast<int>(rng() % 4);
    StaticArena<4096> arena;
    auto stats = mean_filter_disparity(m.view(), out.view(), p, arena.arena());
    ASSERT_TRUE(stats.ok());
    long kept = 0;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        if (!is_valid_disparity(m.at(x, y))) continue;
        const bool keep = keep_reference(m, x, y, p);
        kept += keep;
        EXPECT_EQ(is_valid_disparity(out.at(x, y)), keep) << x << "," << y;
      }
    EXPECT_EQ(stats->after, kept);
    EXPECT_EQ(stats->before, stats->after + stats->removed_spikes + stats->removed_isolated);
  }
}

TEST(DisparityFilter, BadParametersAndSizesAreNamed) {
  Map m(10, 10), out(10, 10), small(5, 10);
  StaticArena<4096> arena;
  MeanFilterParams p;
  p.window = 4;
  auto r = mean_filter_disparity(m.view(), out.view(), p, arena.arena());
  ASSERT_FALSE(r.ok());
  EXPECT_NE(std::string(r.error().message).find("window"), std::string::npos);
  p = {};
  p.tolerance_px = 0;
  r = mean_filter_disparity(m.view(), out.view(), p, arena.arena());
  EXPECT_NE(std::string(r.error().message).find("tolerance"), std::string::npos);
  p = {};
  p.min_support = 25;
  r = mean_filter_disparity(m.view(), out.view(), p, arena.arena());
  EXPECT_NE(std::string(r.error().message).find("min_support"), std::string::npos);
  r = mean_filter_disparity(m.view(), small.view(), MeanFilterParams{}, arena.arena());
  EXPECT_EQ(r.code(), Errc::invalid_argument);
  r = mean_filter_disparity(m.view(), m.view(), MeanFilterParams{}, arena.arena());
  EXPECT_NE(std::string(r.error().message).find("aliases"), std::string::npos);
  StaticArena<16> tiny;
  r = mean_filter_disparity(m.view(), out.view(), MeanFilterParams{}, tiny.arena());
  EXPECT_EQ(r.code(), Errc::capacity_exceeded);
}

TEST(DisparityFilter, NoHeapAndScratchAsDeclared) {
  Map m(200, 150), out(200, 150);
  for (auto& q : m.q) q = disparity_q4(12.5);
  std::vector<std::byte> block(mean_filter_scratch_bytes(200));
  Arena arena(block);
  test::HeapScope scope;
  auto stats = mean_filter_disparity(m.view(), out.view(), MeanFilterParams{}, arena);
  EXPECT_EQ(scope.allocations(), 0u);
  ASSERT_TRUE(stats.ok()) << stats.error().message;
  EXPECT_EQ(stats->after, 200 * 150);
}

}  // namespace
}  // namespace petra
