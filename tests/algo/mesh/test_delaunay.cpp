#include "algo/mesh/delaunay.hpp"

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

enum class Strategy { automatic, incremental, raster };

Result<Run> triangulate(const std::vector<IntPoint>& pts, Strategy how = Strategy::automatic) {
  std::vector<std::byte> block(delaunay_scratch_bytes(pts.size()));
  Arena arena(block);
  Run run;
  run.tris.resize(delaunay_max_triangles(pts.size()));
  auto stats = how == Strategy::incremental ? delaunay_triangulate_incremental(pts, run.tris, arena)
               : how == Strategy::raster    ? delaunay_triangulate_raster(pts, run.tris, arena)
                                            : delaunay_triangulate(pts, run.tris, arena);
  if (!stats) return stats.error();
  run.stats = *stats;
  run.tris.resize(stats->triangles);
  return run;
}

// Convex hull boundary points (collinear ones included): strict hull by the
// monotone chain, then every point lying on one of its edges.
std::size_t hull_boundary_points(std::vector<IntPoint> pts) {
  std::sort(pts.begin(), pts.end(),
            [](auto a, auto b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
  pts.erase(std::unique(pts.begin(), pts.end()), pts.end());
  std::vector<IntPoint> hull;
  for (int pass = 0; pass < 2; ++pass) {
    const std::size_t base = hull.size();
    for (std::size_t k = 0; k < pts.size(); ++k) {
      const IntPoint p = pass == 0 ? pts[k] : pts[pts.size() - 1 - k];
      while (hull.size() >= base + 2 && orient2d(hull[hull.size() - 2], hull.back(), p) <= 0)
        hull.pop_back();
      hull.push_back(p);
    }
    hull.pop_back();
  }
  std::size_t on = 0;
  for (const IntPoint& q : pts)
    for (std::size_t e = 0; e < hull.size(); ++e) {
      const IntPoint a = hull[e], b = hull[(e + 1) % hull.size()];
      if (orient2d(a, b, q) == 0 && std::min(a.x, b.x) <= q.x && q.x <= std::max(a.x, b.x) &&
          std::min(a.y, b.y) <= q.y && q.y <= std::max(a.y, b.y)) {
        ++on;
        break;
      }
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
  for (int trial = 0; trial < 8; ++trial) {
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

TEST(Delaunay, RasterAndIncrementalPathsBothGiveDelaunay) {
  std::mt19937 rng(21);
  for (int trial = 0; trial < 6; ++trial) {
    std::vector<IntPoint> pts;
    if (trial < 3) {
      // Grid with holes of growing density, like a disparity map.
      for (int y = 0; y < 25; ++y)
        for (int x = 0; x < 30; ++x)
          if (static_cast<int>(rng() % 10) >= 2 * trial) pts.push_back({x, y});
    } else {
      // Scattered points (not a grid) put in raster order; a few rows hold one point.
      std::set<std::pair<int, int>> yx;
      while (yx.size() < 250)
        yx.insert({static_cast<int>(rng() % 60), static_cast<int>(rng() % 400)});
      for (const auto& [y, x] : yx) pts.push_back({x, y});
    }
    ASSERT_TRUE(is_raster_ordered(pts));
    auto raster = triangulate(pts, Strategy::raster);
    ASSERT_TRUE(raster.ok()) << raster.error().message;
    check_delaunay(pts, *raster);
    auto incremental = triangulate(pts, Strategy::incremental);
    ASSERT_TRUE(incremental.ok());
    EXPECT_EQ(raster->tris.size(), incremental->tris.size());
    EXPECT_EQ(raster->stats.hull_edges, incremental->stats.hull_edges);
  }
  // Out-of-order input is refused by the raster path, accepted by the dispatcher.
  std::vector<IntPoint> unordered = {{5, 0}, {0, 0}, {0, 5}, {5, 5}};
  EXPECT_EQ(triangulate(unordered, Strategy::raster).code(), Errc::invalid_argument);
  EXPECT_TRUE(triangulate(unordered).ok());
  // A single column (collinear, raster ordered) is an error on both paths.
  std::vector<IntPoint> column = {{3, 0}, {3, 1}, {3, 2}, {3, 3}};
  EXPECT_EQ(triangulate(column, Strategy::raster).code(), Errc::degenerate);
  EXPECT_EQ(triangulate(column, Strategy::incremental).code(), Errc::degenerate);
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
