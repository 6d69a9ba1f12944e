#include "algo/surface/support_surface.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "tests/support/heap_counter.hpp"

namespace petra {
namespace {

// A rounded rock (a spherical cap, 60 mm high) on flat ground z = 0, sampled
// on a 2 mm grid seen from above (+z out of the rock, towards the camera); the
// region grown from the click holds the rock and, as where the growth crossed
// a gradual foot, the ground within 130 mm of the rock's axis.
struct Scene {
  std::vector<Eigen::Vector3d> xyz;
  std::vector<PointClass> labels;
  std::size_t top = 0;  // the rock's top
  std::size_t low = 0;  // on the rock's flank, 10 mm above the ground
};

Scene make_scene() {
  Scene s;
  const double radius = 100, sag = 40;  // sphere centre 40 mm under the ground
  double best_low = 1e9;
  for (int y = -200; y <= 200; y += 2)
    for (int x = -200; x <= 200; x += 2) {
      const double r2 = double(x) * x + double(y) * y;
      const double z =
          r2 < radius * radius ? std::max(0.0, std::sqrt(radius * radius - r2) - sag) : 0.0;
      s.xyz.emplace_back(x, y, z);
      s.labels.push_back(r2 < 130.0 * 130.0 ? PointClass::rock : PointClass::ground);
      if (x == 0 && y == 0) s.top = s.xyz.size() - 1;
      if (y == 0 && x > 0 && std::abs(z - 10) < best_low) {
        best_low = std::abs(z - 10);
        s.low = s.xyz.size() - 1;
      }
    }
  return s;
}

// The ground's plane as a grind plane of the region would give it: a patch
// in front of the rock, 0.3 mm RMS.
SupportPlane ground_patch() {
  return {Eigen::Vector3d::UnitZ(), {0, -110, 0}, 2000, 0.3};
}

// A face of the rock: its plane tangent at the top.
SupportPlane top_face() {
  return {Eigen::Vector3d::UnitZ(), {0, 0, 60}, 2000, 0.3};
}

TEST(SupportSurface, TheGroundUnderTheClickedRockIsTheSupport) {
  const Scene s = make_scene();
  const SupportParams p;
  const RockInFront g = rock_in_front(s.xyz, s.labels, s.top, ground_patch(), p);
  EXPECT_GT(g.share(), 0.25);
  EXPECT_NEAR(g.click_height_mm, 60.0, 1e-9);
  EXPECT_TRUE(stands_on(g, p));
  const RockInFront f = rock_in_front(s.xyz, s.labels, s.top, top_face(), p);
  EXPECT_EQ(f.in_front, 0u);  // the rock lies behind its own face's plane
  EXPECT_FALSE(stands_on(f, p));
}

TEST(SupportSurface, AClickNearThePlaneDoesNotStandOnIt) {
  // The rock rises in front of the plane, but the click is 10 mm above it,
  // under the plane's radius (25 mm): the operator may have clicked that face.
  const Scene s = make_scene();
  const SupportParams p;
  const RockInFront g = rock_in_front(s.xyz, s.labels, s.low, ground_patch(), p);
  EXPECT_GT(g.share(), 0.25);
  EXPECT_LT(g.click_height_mm, g.plane_radius_mm);
  EXPECT_FALSE(stands_on(g, p));
}

TEST(SupportSurface, DropsTheGroundNearThePlaneAndKeepsTheRock) {
  Scene s = make_scene();
  const SupportParams p;
  const double r = p.radius_factor * std::sqrt(2000 / 3.14159265358979323846);
  test::HeapScope scope;
  const std::size_t dropped = drop_support(s.xyz, s.labels, ground_patch(), p);
  EXPECT_EQ(scope.allocations(), 0u);
  EXPECT_GT(dropped, 0u);
  for (std::size_t i = 0; i < s.xyz.size(); ++i) {
    const Eigen::Vector3d d = s.xyz[i] - Eigen::Vector3d(0, -110, 0);
    const bool near = std::hypot(d.x(), d.y()) < r;
    if (s.xyz[i].z() > 1.0) {
      EXPECT_EQ(s.labels[i], PointClass::rock) << i;  // the rock
    } else if (near && s.xyz[i].z() == 0.0) {
      EXPECT_EQ(s.labels[i], PointClass::ground) << i;
    }
  }
}

TEST(SupportSurface, BadParametersAreNamed) {
  SupportParams p;
  EXPECT_TRUE(validate(p).ok());
  p.max_share = 1.0;
  EXPECT_EQ(validate(p).code(), Errc::invalid_argument);
  p = {};
  p.click_radii = 0;
  EXPECT_EQ(validate(p).code(), Errc::invalid_argument);
  p = {};
  p.radius_factor = -1;
  EXPECT_EQ(validate(p).code(), Errc::invalid_argument);
}

}  // namespace
}  // namespace petra
