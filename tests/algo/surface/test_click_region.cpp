#include "algo/surface/click_region.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "tests/support/heap_counter.hpp"

namespace petra {
namespace {

// A height field on a 1 mm grid seen from above (+z towards the camera): flat
// ground z = 0 with a rock: a spherical cap (convex, meeting the ground at a
// concave foot 50 deg steep) and, beside it, a second cap against the first (a
// concave crease where they meet). Normals smoothed over 9 x 9 samples as surface_normals
// gives them, so a crease turns over several mesh edges.
struct Field {
  int w = 0, h = 0;
  std::vector<Eigen::Vector3d> xyz, normals;
  std::vector<MeshTriangle> mesh;
  std::size_t at(int x, int y) const { return static_cast<std::size_t>(y) * w + x; }
};

double cap(double x, double y, double cx, double cy, double radius) {
  const double r2 = (x - cx) * (x - cx) + (y - cy) * (y - cy);
  const double sag = 0.64 * radius;  // sphere centre below the ground: the foot is 50 deg steep
  return r2 < radius * radius ? std::max(0.0, std::sqrt(radius * radius - r2) - sag) : 0.0;
}

Field make_field(bool neighbour) {
  Field f;
  f.w = 200;
  f.h = 120;
  auto z = [&](double x, double y) {
    const double a = cap(x, y, 60, 60, 60);
    return neighbour ? std::max(a, cap(x, y, 135, 60, 50)) : a;
  };
  std::vector<Eigen::Vector3d> raw;
  for (int y = 0; y < f.h; ++y)
    for (int x = 0; x < f.w; ++x) {
      f.xyz.emplace_back(x, y, z(x, y));
      const double dx = (z(x + 0.5, y) - z(x - 0.5, y)), dy = (z(x, y + 0.5) - z(x, y - 0.5));
      raw.push_back(Eigen::Vector3d(-dx, -dy, 1).normalized());
    }
  f.normals.assign(raw.size(), Eigen::Vector3d::Zero());
  for (int y = 4; y < f.h - 4; ++y)
    for (int x = 4; x < f.w - 4; ++x) {
      Eigen::Vector3d s = Eigen::Vector3d::Zero();
      for (int j = -4; j <= 4; ++j)
        for (int i = -4; i <= 4; ++i) s += raw[f.at(x + i, y + j)];
      f.normals[f.at(x, y)] = s.normalized();
    }
  for (int y = 0; y + 1 < f.h; ++y)
    for (int x = 0; x + 1 < f.w; ++x) {
      const int a = static_cast<int>(f.at(x, y)), b = static_cast<int>(f.at(x + 1, y));
      const int c = static_cast<int>(f.at(x, y + 1)), d = static_cast<int>(f.at(x + 1, y + 1));
      f.mesh.push_back({{a, b, c}, {-1, -1, -1}});
      f.mesh.push_back({{b, d, c}, {-1, -1, -1}});
    }
  return f;
}

struct Grown {
  Result<ClickRegionResult> result;
  std::vector<PointClass> labels;
};

Grown grow(const Field& f, std::size_t seed, const ClickRegionParams& p = {}) {
  std::vector<std::byte> block(click_region_scratch_bytes(f.xyz.size(), f.mesh.size()) + 256);
  Arena arena(block);
  Grown g{Error::make(Errc::not_ready, "not run"), std::vector<PointClass>(f.xyz.size())};
  g.result = grow_click_region(f.xyz, f.normals, f.mesh, seed, p, g.labels, arena);
  return g;
}

TEST(ClickRegion, GrowsOverTheRockAndStopsAtItsFoot) {
  const Field f = make_field(false);
  const Grown g = grow(f, f.at(60, 50));  // a face of the rock
  ASSERT_TRUE(g.result.ok()) << g.result.error().message;
  std::size_t rock_in = 0, rock = 0, ground_in = 0, ground = 0;
  for (std::size_t i = 0; i < f.xyz.size(); ++i) {
    const bool is_rock = f.xyz[i].z() > 5;  // clear of the smoothed foot
    const bool is_ground = f.xyz[i].z() == 0 && (f.xyz[i] - Eigen::Vector3d(60, 60, 0)).norm() > 52;
    rock += is_rock;
    ground += is_ground;
    rock_in += is_rock && g.labels[i] == PointClass::rock;
    ground_in += is_ground && g.labels[i] == PointClass::rock;
  }
  EXPECT_EQ(rock_in, rock);  // all of the convex rock
  EXPECT_EQ(ground_in, 0u);  // the concave foot does
  EXPECT_GT(g.result->stopped_concave, 0u);
}

TEST(ClickRegion, StopsWhereTwoRocksTouch) {
  const Field f = make_field(true);
  const Grown g = grow(f, f.at(60, 50));
  ASSERT_TRUE(g.result.ok()) << g.result.error().message;
  std::size_t other = 0;
  for (std::size_t i = 0; i < f.xyz.size(); ++i)
    other += f.xyz[i].x() > 112 && f.xyz[i].z() > 5 && g.labels[i] == PointClass::rock;
  EXPECT_EQ(other, 0u);
  EXPECT_EQ(g.labels[f.at(60, 60)], PointClass::rock);
}

TEST(ClickRegion, TooSmallAndBadInputAreNamed) {
  const Field f = make_field(false);
  ClickRegionParams p;
  p.min_points = f.xyz.size() + 1;
  Grown g = grow(f, f.at(60, 50), p);
  ASSERT_FALSE(g.result.ok());
  EXPECT_NE(std::string(g.result.error().message).find("too small"), std::string::npos);
  g = grow(f, f.xyz.size());
  EXPECT_EQ(g.result.code(), Errc::out_of_range);
  p = {};
  p.max_concave_step_deg = 0;
  g = grow(f, 0, p);
  EXPECT_EQ(g.result.code(), Errc::invalid_argument);
  p = {};
  p.min_share = 1.0;
  g = grow(f, 0, p);
  EXPECT_NE(std::string(g.result.error().message).find("min_share"), std::string::npos);
}

TEST(ClickRegion, NoHeap) {
  const Field f = make_field(true);
  std::vector<std::byte> block(click_region_scratch_bytes(f.xyz.size(), f.mesh.size()) + 256);
  Arena arena(block);
  std::vector<PointClass> labels(f.xyz.size());
  test::HeapScope scope;
  auto r = grow_click_region(f.xyz, f.normals, f.mesh, f.at(60, 50), {}, labels, arena);
  EXPECT_EQ(scope.allocations(), 0u);
  EXPECT_TRUE(r.ok());
  EXPECT_EQ(arena.mark(), 0u);  // scratch released
}

}  // namespace
}  // namespace petra
