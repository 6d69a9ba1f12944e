#include "algo/stereo/canny.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "tests/support/heap_counter.hpp"
#include "tests/support/owned_gray_image.hpp"

namespace petra {
namespace {

using Image = test::OwnedGray8;

struct Detector {
  std::vector<std::byte> scratch;
  Arena arena;
  Image edges;
  Detector(int w, int h) : scratch(canny_scratch_bytes(w, h)), arena(scratch), edges(w, h) {}
  Result<CannyStats> operator()(Image& img, Rect area, CannyParams p = {}) {
    return canny(img.view(), area, p, arena, edges.view());
  }
};

TEST(Canny, VerticalStepGivesOneThinColumnWithItsDirection) {
  Image img(40, 30, 50);
  for (int y = 0; y < 30; ++y)
    for (int x = 20; x < 40; ++x) img.at(x, y) = 150;
  Detector run(40, 30);
  auto s = run(img, {0, 0, 40, 30});
  ASSERT_TRUE(s.ok()) << s.error().message;
  for (int y = 0; y < 30; ++y) {
    int count = 0, where = -1;
    for (int x = 0; x < 40; ++x)
      if (is_edge(run.edges.at(x, y))) {
        ++count;
        where = x;
        EXPECT_EQ(edge_sector(run.edges.at(x, y)), kSectorHorizontal);
        EXPECT_EQ(run.edges.at(x, y) & kEdgeGxNegative, 0);  // dark to bright
      }
    EXPECT_EQ(count, 1) << "row " << y;  // thin: non-maximum suppression
    EXPECT_TRUE(where == 19 || where == 20) << where;
  }
  EXPECT_EQ(s->edge_pixels, 30);
}

TEST(Canny, HorizontalAndDiagonalEdgesGetTheirSectors) {
  Image img(40, 40, 60);
  for (int y = 20; y < 40; ++y)
    for (int x = 0; x < 40; ++x) img.at(x, y) = 180;
  Detector run(40, 40);
  ASSERT_TRUE(run(img, {0, 0, 40, 40}).ok());
  for (int x = 0; x < 40; ++x) {
    bool found = false;
    for (int y = 18; y < 22; ++y)
      if (is_edge(run.edges.at(x, y))) {
        found = true;
        EXPECT_EQ(edge_sector(run.edges.at(x, y)), kSectorVertical);
      }
    EXPECT_TRUE(found) << x;
  }
  Image diag(40, 40, 60);
  for (int y = 0; y < 40; ++y)
    for (int x = 0; x < 40; ++x)
      if (x + y > 40) diag.at(x, y) = 180;
  ASSERT_TRUE(run(diag, {0, 0, 40, 40}).ok());
  int diagonal = 0, total = 0;
  for (int y = 5; y < 35; ++y)
    for (int x = 5; x < 35; ++x)
      if (is_edge(run.edges.at(x, y))) {
        ++total;
        diagonal += edge_sector(run.edges.at(x, y)) == kSectorDiagonal;
      }
  EXPECT_GT(total, 25);
  EXPECT_EQ(diagonal, total);
}

TEST(Canny, FlatAndNoisyFlatImagesHaveNoEdges) {
  Image flat(50, 50, 90);
  Detector run(50, 50);
  auto a = run(flat, {0, 0, 50, 50});
  ASSERT_TRUE(a.ok());
  EXPECT_EQ(a->edge_pixels, 0);
  std::mt19937 rng(2);
  std::normal_distribution<double> n(0.0, 2.0);
  for (auto& v : flat.px) v = static_cast<std::uint8_t>(std::lround(90 + n(rng)));
  auto b = run(flat, {0, 0, 50, 50});
  ASSERT_TRUE(b.ok());
  EXPECT_EQ(b->edge_pixels, 0);  // noise of 2 gray levels stays below the thresholds
}

TEST(Canny, HysteresisKeepsWeakEdgesOnlyWhenConnectedToStrongOnes) {
  // Left contour: a vertical step whose height fades from 60 (strong) at the
  // top to 14 (weak) at the bottom, slowly enough to make no horizontal edge.
  // Right contour: a step of 14 everywhere, weak and unconnected.
  Image img(60, 40, 100);
  for (int y = 0; y < 40; ++y) {
    const int fade = 60 - (46 * y) / 39;
    for (int x = 15; x < 60; ++x) img.at(x, y) = static_cast<std::uint8_t>(100 + fade);
    for (int x = 40; x < 60; ++x) img.at(x, y) = static_cast<std::uint8_t>(img.at(x, y) + 14);
  }
  Detector run(60, 40);
  CannyParams p;
  p.low = 20;
  p.high = 80;
  auto s = run(img, {0, 0, 60, 40}, p);
  ASSERT_TRUE(s.ok());
  int left = 0, right = 0;
  for (int y = 0; y < 40; ++y)
    for (int x = 0; x < 60; ++x)
      if (is_edge(run.edges.at(x, y))) (x < 30 ? left : right)++;
  EXPECT_EQ(left, 40);  // the whole left contour, grown from its strong part
  EXPECT_LT(s->strong_pixels, 40);
  EXPECT_EQ(right, 0);  // weak and unconnected
}

TEST(Canny, AreaInsideALargerImageSeesItsSurroundings) {
  Image img(80, 60, 40);
  for (int y = 0; y < 60; ++y)
    for (int x = 30; x < 80; ++x) img.at(x, y) = 200;
  Detector run(20, 20);
  ASSERT_TRUE(run(img, {21, 10, 20, 20}).ok());
  for (int y = 0; y < 20; ++y) {
    int count = 0;
    for (int x = 0; x < 20; ++x) count += is_edge(run.edges.at(x, y));
    EXPECT_EQ(count, 1);  // the step at x = 29/30 is column 8/9 of the area
  }
}

TEST(Canny, DenseTextureStaysWithinTheBoundedStack) {
  // Random noise with the lowest thresholds: every ridge of the gradient is
  // an edge and the hysteresis stack sees the worst case it can.
  Image img(64, 64);
  std::mt19937 rng(12);
  for (auto& v : img.px) v = static_cast<std::uint8_t>(rng() % 256);
  Detector run(64, 64);
  auto s = run(img, {0, 0, 64, 64}, CannyParams{1, 1});
  ASSERT_TRUE(s.ok());
  EXPECT_GT(s->edge_pixels, 64 * 64 / 4);
}

TEST(Canny, BadInputNamesTheProblem) {
  Image img(30, 30, 10);
  Detector run(30, 30);
  EXPECT_EQ(run(img, {0, 0, 0, 10}).code(), Errc::invalid_argument);
  auto a = run(img, {20, 20, 30, 30});
  EXPECT_EQ(a.code(), Errc::out_of_range);
  EXPECT_NE(std::strstr(a.error().message, "outside"), nullptr);
  auto b = run(img, {0, 0, 20, 20});  // edges buffer is 30x30
  EXPECT_EQ(b.code(), Errc::invalid_argument);
  EXPECT_NE(std::strstr(b.error().message, "edges are 30x30"), nullptr);
  auto c = run(img, {0, 0, 30, 30}, CannyParams{50, 10});
  EXPECT_EQ(c.code(), Errc::invalid_argument);
  EXPECT_NE(std::strstr(c.error().message, "thresholds"), nullptr);
  std::vector<std::byte> tiny(100);
  Arena small(tiny);
  auto d = canny(img.view(), {0, 0, 30, 30}, {}, small, run.edges.view());
  EXPECT_EQ(d.code(), Errc::capacity_exceeded);
  EXPECT_NE(std::strstr(d.error().message, "canny"), nullptr) << d.error().message;
}

TEST(Canny, ScratchIsReleasedAndNothingIsAllocated) {
  Image img(64, 48);
  std::mt19937 rng(9);
  for (auto& v : img.px) v = static_cast<std::uint8_t>(rng() % 256);
  Detector run(64, 48);
  petra::test::HeapScope scope;
  for (int i = 0; i < 5; ++i) {
    ASSERT_TRUE(run(img, {0, 0, 64, 48}).ok());
    EXPECT_EQ(run.arena.used(), 0u);
  }
  EXPECT_LE(run.arena.high_water(), canny_scratch_bytes(64, 48));
  EXPECT_EQ(scope.allocations(), 0u);
}

}  // namespace
}  // namespace petra
