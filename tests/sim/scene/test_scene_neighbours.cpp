// The operator's hard cases (docs/scene.md "Neighbours and a rock filling the
// ROI"), checked against the rays the renderer casts: neighbours touch the
// rock (closest distance <= 2 mm, no overlap), never hide a grind face from
// either camera and show in the left image; the --roi-fill ROI holds no
// ground, stone or neighbour pixel; the click lies on the lit rock in the ROI.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "sim/scene/camera_rays.hpp"
#include "sim/scene/neighbours.hpp"
#include "sim/scene/ray_cast.hpp"
#include "sim/scene/scene_geometry.hpp"
#include "sim/scene/scene_set.hpp"
#include "sim/scene/truth_pixels.hpp"
#include "tests/sim/scene/independent_scene_check.hpp"

namespace petra::sim {
namespace {

SceneOptions real_options(std::uint64_t seed, int neighbours) {
  SceneOptions o = standard_scene_set()[static_cast<std::size_t>(seed % 24)];
  o.seed = seed;
  o.world = realistic_world();
  o.neighbours = neighbours;
  return o;
}

// Distance from p (outside) to the rock's surface above the ground.
double distance_to_rock(const ConvexRock& r, const Eigen::Vector3d& p) {
  double d = INFINITY;
  for (const auto& f : r.faces) {
    const Polygon3 e = exposed_polygon(f);
    if (e.size() >= 3) d = std::min(d, distance_to_polygon(e, f.plane.normal, p));
  }
  return d;
}

TEST(SceneNeighbours, CountIsValidatedByName) {
  SceneOptions o = real_options(2024, 4);
  Status st = validate(o);
  ASSERT_FALSE(st.ok());
  EXPECT_EQ(std::string(st.error().message).rfind("neighbours = 4", 0), 0u) << st.error().message;
  o.neighbours = -1;
  EXPECT_FALSE(validate(o).ok());
  o.neighbours = 3;
  EXPECT_TRUE(validate(o).ok());
}

TEST(SceneNeighbours, TouchTheRockAndNeverHideAGrindFace) {
  for (std::uint64_t seed : {2024u, 2025u, 2027u}) {
    auto scene = make_scene(real_options(seed, 2));
    ASSERT_TRUE(scene) << scene.error().message;
    const Scene& s = *scene;
    ASSERT_EQ(s.neighbours.size(), 2u) << seed;
    const Eigen::Vector3d cams[2] = {camera_centre_world(s.rig.left),
                                     camera_centre_world(s.rig.right)};
    for (const ConvexRock& nb : s.neighbours) {
      double closest = INFINITY, overlap = 0;
      for (const auto& p : check::exposed_edge_points(nb)) {
        closest = std::min(closest, distance_to_rock(s.rock, p));
        overlap = std::max(overlap, check::depth_inside(s.rock, p));
      }
      for (const auto& p : check::exposed_edge_points(s.rock)) {
        closest = std::min(closest, distance_to_rock(nb, p));
        overlap = std::max(overlap, check::depth_inside(nb, p));
      }
      EXPECT_LE(closest, 2.0) << "seed " << seed << ": neighbour does not touch the rock";
      EXPECT_LE(overlap, 0.05) << "seed " << seed << ": neighbour overlaps the rock";
    }
    // Every point of a grind face is the first thing each camera sees there.
    int grind_points = 0;
    for (const auto& f : visible_facets(s)) {
      if (!f.grind_face) continue;
      const Eigen::Vector3d c = f.centroid;
      for (const auto& v : f.polygon)
        for (double w : {0.0, 0.5, 0.9}) {
          const Eigen::Vector3d p = c + w * (v - c);
          for (const auto& cam : cams) {
            const SceneHit hit = trace(s, cam, (p - cam).normalized());
            EXPECT_FALSE(is_neighbour(hit.surface)) << "seed " << seed << ": grind face hidden";
            ++grind_points;
          }
        }
    }
    EXPECT_GT(grind_points, 20);
    // Each neighbour shows in the left image.
    for (std::size_t k = 0; k < s.neighbours.size(); ++k) {
      int seen = 0;
      for (const auto& f : s.neighbours[k].faces)
        for (const auto& p : exposed_polygon(f)) {
          const Eigen::Vector3d q = p + 0.2 * (s.neighbours[k].centre - p);
          const SceneHit hit = trace(s, cams[0], (q - cams[0]).normalized());
          seen += hit.surface / kNeighbourFaces == (kNeighbour0 / kNeighbourFaces) + int(k);
        }
      EXPECT_GT(seen, 0) << "seed " << seed << ": neighbour " << k << " not seen";
    }
  }
}

// Pixel square corners and centre of every pixel in `r`, 4 x 4 samples each.
bool only_rock_in(const Scene& s, const Rect& r, int& bad) {
  const CameraRays rays(s.rig.left);
  bad = 0;
  for (int v = r.y; v < r.y + r.h; ++v)
    for (int u = r.x; u < r.x + r.w; ++u)
      for (int b = 0; b < 4; ++b)
        for (int a = 0; a < 4; ++a) {
          const SceneHit hit =
              trace(s, rays.origin(), rays.direction(u - 0.375 + 0.25 * a, v - 0.375 + 0.25 * b));
          bad += is_target_face(hit.surface) ? 0 : 1;
        }
  return bad == 0;
}

TEST(SceneRoiFill, RoiHoldsNoGroundAndTheClickIsOnTheLitRock) {
  for (std::uint64_t seed : {2028u, 2031u}) {
    SceneOptions o = real_options(seed, 0);
    o.roi_fill = true;
    auto scene = make_scene(o);
    ASSERT_TRUE(scene) << scene.error().message;
    const Scene& s = *scene;
    const Rect whole{0, 0, kImageWidth, kImageHeight};
    // The rock's outline bounds the search (as the truth's ROI does).
    double u0 = INFINITY, v0 = INFINITY, u1 = -INFINITY, v1 = -INFINITY;
    for (const auto& p : rock_outline_points(s.rock, 8)) {
      auto uv = project(s.rig.left, p);
      ASSERT_TRUE(uv);
      u0 = std::min(u0, uv->x()), v0 = std::min(v0, uv->y());
      u1 = std::max(u1, uv->x()), v1 = std::max(v1, uv->y());
    }
    const Rect around{int(u0) - 2, int(v0) - 2, int(u1 - u0) + 5, int(v1 - v0) + 5};
    ASSERT_TRUE(around.x >= 0 && around.y >= 0 && around.x + around.w <= whole.w);
    const Rect roi = roi_inside_rock(s, around);
    EXPECT_GT(roi.w * roi.h, 0.25 * around.w * around.h) << "seed " << seed;
    int bad = 0;
    EXPECT_TRUE(only_rock_in(s, roi, bad))
        << "seed " << seed << ": " << bad << " samples off the rock";
    const auto facets = visible_facets(s);
    const auto click = click_on_rock(s, roi, facets);
    ASSERT_TRUE(click) << seed;
    EXPECT_TRUE(click->x() >= roi.x && click->x() < roi.x + roi.w && click->y() >= roi.y &&
                click->y() < roi.y + roi.h);
    const CameraRays rays(s.rig.left);
    const SceneHit hit = trace(s, rays.origin(), rays.direction(click->x(), click->y()));
    EXPECT_TRUE(is_target_face(hit.surface)) << seed;
    EXPECT_FALSE(in_shadow(s, hit)) << seed;
  }
}

// The realistic set: entries 0..23 as before, then 4 with 1-2 neighbours and
// 4 filling the ROI, the boundary x sun x shape x faces cycle kept.
TEST(SceneRoiFill, RealSetEndsWithTheHardCases) {
  const auto set = real_scene_set();
  ASSERT_EQ(set.size(), 32u);
  const auto standard = standard_scene_set();
  for (std::size_t k = 0; k < set.size(); ++k) {
    const bool neighbours = k >= 24 && k < 28, fill = k >= 28;
    EXPECT_EQ(set[k].neighbours > 0, neighbours) << k;
    EXPECT_EQ(set[k].roi_fill, fill) << k;
    EXPECT_EQ(set[k].seed, 2000 + k);
    EXPECT_EQ(set[k].flat_faces, standard[k % 24].flat_faces) << k;
    EXPECT_EQ(set[k].shape, standard[k % 24].shape) << k;
  }
}

}  // namespace
}  // namespace petra::sim
