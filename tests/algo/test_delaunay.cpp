#include "algo/delaunay.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>
#include <vector>

#include "tests/support/heap_counter.hpp"

namespace petra {
namespace {

struct Run {
  DelaunayStats stats;
  std::vector<MeshTriangle> tris;
};

Result<Run> triangulate(const std::vector<IntPoint>& pts) {
  std::vector<std::byte> block(delaunay_scratch_bytes(pts.size()));
  Arena arena(block);
  Run run;
  run.tris.resize(delaunay_max_triangles(pts.size()));
  auto stats = delaunay_triangulate(pts, run.tris, arena);
  if (!stats) return stats.error();
  run.stats = *stats;
  run.tris.resize(stats->triangles);
  return run;
}

// Convex hull boundary points (collinear ones included), by brute force over
// the monotone chain with collinear points kept.
std::size_t hull_boundary_points(std::vector<IntPoint> pts) {
  std::sort(pts.begin(), pts.end(),
            [](auto a, auto b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
  pts.erase(std::unique(pts.begin(), pts.end()), pts.end());
  std::size_t on = 0;
  for (const IntPoint& q : pts) {
    // q is on the boundary iff some line through q has every point on one closed side.
    bool boundary = false;
    for (const IntPoint& r : pts) {
      if (r == q) continue;
      bool left = true, right = true;
      for (const IntPoint& s : pts) {
        const std::int64_t o = orient2d(q, r, s);
        if (o > 0) right = false;
        if (o < 0) left = false;
      }
      if (left || right) {
        boundary = true;
        break;
      }
    }
    on += boundary;
  }
  return on;
}

// Everything a Delaunay triangulation must satisfy, checked by brute force.
void check_delaunay(const std::vector<IntPoint>& pts, const Run& run, bool count_hull = true) {
  std::set<std::pair<int, int>> unique_pts;
  for (const auto& p : pts) unique_pts.insert({p.x, p.y});
  const std::size_t nv = unique_pts.size();
  EXPECT_EQ(run.stats.vertices, nv);
  EXPECT_EQ(run.stats.duplicates, pts.size() - nv);
  EXPECT_EQ(run.stats.walk_fallbacks, 0u);
  std::set<int> used;
  for (std::size_t t = 0; t < run.tris.size(); ++t) {
    const MeshTriangle& tri = run.tris[t];
    const IntPoint a = pts[tri.v[0]], b = pts[tri.v[1]], c = pts[tri.v[2]];
    ASSERT_GT(orient2d(a, b, c), 0) << "triangle " << t << " not positively oriented";
    for (int k = 0; k < 3; ++k) used.insert(tri.v[k]);
    // Empty circumcircle: no input point strictly inside.
    for (const IntPoint& p : pts) ASSERT_LE(incircle_sign(a, b, c, p), 0) << "triangle " << t;
    // Neighbours are mutual and share the edge.
    for (int k = 0; k < 3; ++k) {
      const int nb = tri.n[k];
      if (nb < 0) continue;
      const MeshTriangle& o = run.tris[static_cast<std::size_t>(nb)];
      const int e0 = tri.v[(k + 1) % 3], e1 = tri.v[(k + 2) % 3];
      bool back = false;
      for (int j = 0; j < 3; ++j)
        if (o.n[j] == static_cast<int>(t) && o.v[(j + 1) % 3] == e1 && o.v[(j + 2) % 3] == e0)
          back = true;
      EXPECT_TRUE(back) << "neighbour " << nb << " of " << t;
    }
  }
  EXPECT_EQ(used.size(), nv);  // every distinct point is a vertex
  // Euler for a triangulated point set: T = 2V - 2 - h (h: points on the hull).
  const std::size_t h = run.stats.hull_edges;
  EXPECT_EQ(run.tris.size(), 2 * nv - 2 - h);
  if (count_hull) {
    EXPECT_EQ(h, hull_boundary_points(pts));
  }
  // V - E + F = 2 with the outer face.
  std::size_t interior_edges2 = 0;
  for (const auto& tri : run.tris)
    for (int k = 0; k < 3; ++k) interior_edges2 += tri.n[k] >= 0;
  const std::size_t edges = interior_edges2 / 2 + h;
  EXPECT_EQ(
      static_cast<long>(nv) - static_cast<long>(edges) + static_cast<long>(run.tris.size() + 1), 2);
}

TEST(Delaunay, RandomPointsSatisfyTheEmptyCircleProperty) {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 5; ++trial) {
    std::vector<IntPoint> pts(300);
    for (auto& p : pts) p = {static_cast<int>(rng() % 2000) - 1000, static_cast<int>(rng() % 1500)};
    auto run = triangulate(pts);
    ASSERT_TRUE(run.ok()) << run.error().message;
    check_delaunay(pts, *run);
  }
}

TEST(Delaunay, FullAndHoledGridsAreValid) {
  std::vector<IntPoint> grid;
  for (int y = 0; y < 20; ++y)
    for (int x = 0; x < 30; ++x) grid.push_back({100 + x, 50 + y});
  auto run = triangulate(grid);
  ASSERT_TRUE(run.ok()) << run.error().message;
  check_delaunay(grid, *run);
  EXPECT_EQ(run->tris.size(), 2u * 29 * 19);  // every cell split in two
  // Random holes, like invalid disparities.
  std::mt19937 rng(3);
  std::vector<IntPoint> holed;
  for (const auto& p : grid)
    if (rng() % 4 != 0) holed.push_back(p);
  run = triangulate(holed);
  ASSERT_TRUE(run.ok());
  check_delaunay(holed, *run);
}

TEST(Delaunay, CocircularPointsAndTheirCentre) {
  // Every lattice point on x^2 + y^2 = 325^2 (325 = 5^2 * 13 has many).
  std::vector<IntPoint> pts;
  for (int x = -325; x <= 325; ++x)
    for (int y = -325; y <= 325; ++y)
      if (x * x + y * y == 325 * 325) pts.push_back({x, y});
  ASSERT_GT(pts.size(), 20u);
  auto run = triangulate(pts);
  ASSERT_TRUE(run.ok());
  check_delaunay(pts, *run);
  pts.push_back({0, 0});
  run = triangulate(pts);
  ASSERT_TRUE(run.ok());
  check_delaunay(pts, *run);
}

TEST(Delaunay, CollinearInputIsAnErrorOnePointOffMakesAFan) {
  std::vector<IntPoint> line;
  for (int i = 0; i < 50; ++i) line.push_back({3 * i, 2 * i});
  auto run = triangulate(line);
  ASSERT_FALSE(run.ok());
  EXPECT_EQ(run.code(), Errc::degenerate);
  EXPECT_NE(std::string(run.error().message).find("collinear"), std::string::npos);
  line.push_back({10, 100});
  run = triangulate(line);
  ASSERT_TRUE(run.ok()) << run.error().message;
  check_delaunay(line, *run);
  EXPECT_EQ(run->tris.size(), 49u);
}

TEST(Delaunay, DuplicatesAreSkippedAndCounted) {
  std::vector<IntPoint> pts = {{0, 0}, {10, 0}, {0, 10}, {10, 0}, {0, 0}, {10, 10}, {5, 5}, {5, 5}};
  auto run = triangulate(pts);
  ASSERT_TRUE(run.ok());
  EXPECT_EQ(run->stats.duplicates, 3u);
  check_delaunay(pts, *run);
  std::vector<IntPoint> same(10, IntPoint{4, 4});
  auto bad = triangulate(same);
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(std::string(bad.error().message).find("coincide"), std::string::npos);
}

TEST(Delaunay, BadInputIsNamed) {
  std::vector<IntPoint> two = {{0, 0}, {1, 1}};
  auto r = triangulate(two);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(std::string(r.error().message).find("need at least 3"), std::string::npos);
  std::vector<IntPoint> far = {{0, 0}, {1, 0}, {0, 1 << 21}};
  r = triangulate(far);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.code(), Errc::out_of_range);
  // Too small an output span or arena.
  std::vector<IntPoint> pts = {{0, 0}, {10, 0}, {0, 10}, {10, 10}};
  std::vector<std::byte> block(delaunay_scratch_bytes(pts.size()));
  Arena arena(block);
  std::vector<MeshTriangle> out(1);
  auto s = delaunay_triangulate(pts, out, arena);
  EXPECT_EQ(s.code(), Errc::capacity_exceeded);
  StaticArena<64> tiny;
  out.resize(8);
  s = delaunay_triangulate(pts, out, tiny.arena());
  EXPECT_EQ(s.code(), Errc::capacity_exceeded);
}

TEST(Delaunay, LargeDisparityLikeSetWithoutHeap) {
  // 25,000 grid points with 10 % holes, the pipeline's size.
  std::mt19937 rng(8);
  std::vector<IntPoint> pts;
  for (int y = 0; y < 160 && pts.size() < 25000; ++y)
    for (int x = 0; x < 180 && pts.size() < 25000; ++x)
      if (rng() % 10 != 0) pts.push_back({400 + x, 300 + y});
  std::vector<std::byte> block(delaunay_scratch_bytes(pts.size()));
  Arena arena(block);
  std::vector<MeshTriangle> out(delaunay_max_triangles(pts.size()));
  test::HeapScope scope;
  auto s = delaunay_triangulate(pts, out, arena);
  EXPECT_EQ(scope.allocations(), 0u);
  ASSERT_TRUE(s.ok()) << s.error().message;
  EXPECT_EQ(s->walk_fallbacks, 0u);
  EXPECT_EQ(s->triangles, 2 * pts.size() - 2 - s->hull_edges);
  EXPECT_EQ(arena.used(), 0u);
  EXPECT_LE(arena.high_water(), delaunay_scratch_bytes(pts.size()));
}

}  // namespace
}  // namespace petra
