#include "algo/mesh/mesh_lift.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "tests/support/heap_counter.hpp"

namespace petra {
namespace {

// A pinhole at the origin looking along +Z (f = 800 px): pixel + depth -> point.
Eigen::Vector3d lift(int u, int v, double z) {
  return {(u - 100) * z / 800.0, (v - 100) * z / 800.0, z};
}

struct LiftScene {
  std::vector<IntPoint> px;
  std::vector<Eigen::Vector3d> xyz;
  std::vector<MeshTriangle> tris;
};

// 60x40 grid: ground at 700 mm, a box (top at box_depth) in the middle.
LiftScene step_scene(double box_depth = 690.0) {
  LiftScene s;
  for (int v = 80; v < 120; ++v)
    for (int u = 70; u < 130; ++u) {
      const bool box = u >= 90 && u < 110 && v >= 90 && v < 110;
      s.px.push_back({u, v});
      s.xyz.push_back(lift(u, v, box ? box_depth : 700.0));
    }
  std::vector<std::byte> block(delaunay_scratch_bytes(s.px.size()));
  Arena arena(block);
  s.tris.resize(delaunay_max_triangles(s.px.size()));
  auto st = delaunay_triangulate(s.px, s.tris, arena);
  EXPECT_TRUE(st.ok());
  s.tris.resize(st->triangles);
  return s;
}

// Triangles with all three vertices on one surface (same depth).
std::size_t pure_triangles(const LiftScene& s) {
  std::size_t pure = 0;
  for (const auto& t : s.tris) {
    const double z0 = s.xyz[t.v[0]].z(), z1 = s.xyz[t.v[1]].z(), z2 = s.xyz[t.v[2]].z();
    pure += z0 == z1 && z1 == z2;
  }
  return pure;
}

TEST(MeshLift, StepTrianglesAreRemovedSurfacesKept) {
  LiftScene s = step_scene();
  const std::size_t before = s.tris.size();
  const std::size_t pure = pure_triangles(s);
  std::vector<std::byte> block(mesh_filter_scratch_bytes(before));
  Arena arena(block);
  test::HeapScope scope;
  auto st =
      remove_discontinuities(s.xyz, Eigen::Vector3d::Zero(), MeshFilterParams{}, s.tris, arena);
  EXPECT_EQ(scope.allocations(), 0u);
  ASSERT_TRUE(st.ok()) << st.error().message;
  s.tris.resize(st->kept);
  // Every kept triangle lies on one surface; every one-surface triangle is kept.
  std::size_t mixed = 0;
  for (const auto& t : s.tris) {
    const double z0 = s.xyz[t.v[0]].z(), z1 = s.xyz[t.v[1]].z(), z2 = s.xyz[t.v[2]].z();
    mixed += !(z0 == z1 && z1 == z2);
  }
  EXPECT_EQ(mixed, 0u);
  EXPECT_GT(st->removed_grazing, 0u);
  EXPECT_EQ(st->removed_long, 0u);
  EXPECT_EQ(st->kept + st->removed_grazing + st->removed_degenerate, before);
  EXPECT_EQ(st->kept, pure);  // and all the one-surface triangles survive
  EXPECT_GT(pure, before * 9 / 10);
  // Neighbour links remain mutual after compaction.
  for (std::size_t i = 0; i < s.tris.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      const int nb = s.tris[i].n[k];
      if (nb < 0) continue;
      ASSERT_LT(static_cast<std::size_t>(nb), s.tris.size());
      const auto& o = s.tris[static_cast<std::size_t>(nb)];
      EXPECT_TRUE(o.n[0] == static_cast<int>(i) || o.n[1] == static_cast<int>(i) ||
                  o.n[2] == static_cast<int>(i));
    }
}

TEST(MeshLift, LongEdgesAreRemoved) {
  LiftScene tall = step_scene(660.0);  // a 40 mm step: its edges exceed 25 mm
  const std::size_t tall_total = tall.tris.size(), tall_pure = pure_triangles(tall);
  std::vector<std::byte> tall_block(mesh_filter_scratch_bytes(tall.tris.size()));
  Arena tall_arena(tall_block);
  auto ts = remove_discontinuities(tall.xyz, Eigen::Vector3d::Zero(), MeshFilterParams{}, tall.tris,
                                   tall_arena);
  ASSERT_TRUE(ts.ok());
  EXPECT_EQ(ts->removed_long, tall_total - tall_pure);
  EXPECT_EQ(ts->removed_grazing, 0u);
  LiftScene s = step_scene();
  std::vector<std::byte> block(mesh_filter_scratch_bytes(s.tris.size()));
  Arena arena(block);
  MeshFilterParams p;
  p.max_edge_mm = 0.5;  // grid spacing is ~0.85 mm: everything goes
  auto st = remove_discontinuities(s.xyz, Eigen::Vector3d::Zero(), p, s.tris, arena);
  ASSERT_TRUE(st.ok());
  EXPECT_EQ(st->kept, 0u);
  EXPECT_EQ(st->removed_long, s.tris.size());
}

TEST(MeshLift, BadParametersAndIndicesAreNamed) {
  LiftScene s = step_scene();
  StaticArena<1 << 16> arena;
  MeshFilterParams p;
  p.max_view_angle_deg = 95;
  auto st = remove_discontinuities(s.xyz, Eigen::Vector3d::Zero(), p, s.tris, arena.arena());
  ASSERT_FALSE(st.ok());
  EXPECT_NE(std::string(st.error().message).find("max_view_angle_deg"), std::string::npos);
  p = {};
  p.max_edge_mm = -1;
  st = remove_discontinuities(s.xyz, Eigen::Vector3d::Zero(), p, s.tris, arena.arena());
  EXPECT_NE(std::string(st.error().message).find("max_edge_mm"), std::string::npos);
  s.tris[3].v[1] = 100000;
  st = remove_discontinuities(s.xyz, Eigen::Vector3d::Zero(), MeshFilterParams{}, s.tris,
                              arena.arena());
  EXPECT_EQ(st.code(), Errc::out_of_range);
}

}  // namespace
}  // namespace petra
