#include "algo/grind_planes.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "algo/ground_segment.hpp"
#include "algo/mesh_lift.hpp"
#include "tests/support/heap_counter.hpp"
#include "tests/support/synthetic_scene.hpp"

namespace petra {
namespace {

const test::PinholeView kView = test::look_at({30, -600, 500}, {0, 0, 20});

struct RockMesh {
  test::Cloud cloud;
  std::vector<MeshTriangle> tris;  // rock triangles only
};

// Cloud -> Delaunay -> lift/filter -> segmentation -> rock triangles.
RockMesh make_rock_mesh(double noise_mm, std::uint64_t seed) {
  RockMesh m;
  const Eigen::Vector2d a = kView.project({-40, -30, 0}), b = kView.project({40, 30, 55});
  const Rect roi{static_cast<int>(std::min(a.x(), b.x())) - 40,
                 static_cast<int>(std::min(a.y(), b.y())) - 40,
                 static_cast<int>(std::abs(b.x() - a.x())) + 80,
                 static_cast<int>(std::abs(b.y() - a.y())) + 80};
  m.cloud = test::render(kView, roi, test::ridge_rock(), noise_mm, seed);
  std::vector<IntPoint> px;
  for (const auto& p : m.cloud.px) px.push_back({p.u, p.v});
  std::vector<std::byte> block(delaunay_scratch_bytes(px.size()) +
                               grind_planes_scratch_bytes(2 * px.size()));
  Arena arena(block);
  m.tris.resize(delaunay_max_triangles(px.size()));
  auto d = delaunay_triangulate(px, m.tris, arena);
  EXPECT_TRUE(d.ok());
  m.tris.resize(d->triangles);
  auto f = remove_discontinuities(m.cloud.xyz, kView.centre(), MeshFilterParams{}, m.tris, arena);
  EXPECT_TRUE(f.ok());
  m.tris.resize(f->kept);
  std::vector<PointClass> labels(m.cloud.xyz.size());
  auto g = segment_ground<double>(m.cloud.xyz, m.cloud.px, roi, {}, kView.centre(), {}, labels);
  EXPECT_TRUE(g.ok()) << g.error().message;
  auto rock = [&](int v) { return labels[static_cast<std::size_t>(v)] == PointClass::rock; };
  auto kept = keep_triangles(
      std::span<MeshTriangle>(m.tris),
      [&](std::size_t i) {
        return rock(m.tris[i].v[0]) && rock(m.tris[i].v[1]) && rock(m.tris[i].v[2]);
      },
      arena);
  EXPECT_TRUE(kept.ok());
  m.tris.resize(*kept);
  return m;
}

// Built once per (noise, seed): the Debug build is slow to ray-cast.
const RockMesh& rock_mesh(double noise_mm, std::uint64_t seed = 1) {
  static const RockMesh exact = make_rock_mesh(0.0, 1);
  static const RockMesh noisy = make_rock_mesh(0.3, 5);
  EXPECT_TRUE((noise_mm == 0.0 && seed == 1) || (noise_mm == 0.3 && seed == 5));
  return noise_mm == 0.0 ? exact : noisy;
}

double angle_deg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b)) * 180 / M_PI;
}

// The rock face a plane belongs to: the face with the closest normal.
int face_of(const test::Rock& rock, const GrindPlane& p) {
  int best = 0;
  for (std::size_t k = 1; k < rock.faces.size(); ++k)
    if (rock.faces[k].n.dot(p.normal) > rock.faces[static_cast<std::size_t>(best)].n.dot(p.normal))
      best = static_cast<int>(k);
  return best;
}

// On face f: inside every other half-space.
bool on_face(const test::Rock& rock, int f, const Eigen::Vector3d& x, double tol) {
  for (std::size_t k = 0; k < rock.faces.size(); ++k) {
    const double d = rock.faces[k].n.dot(x) + rock.faces[k].d;
    if (static_cast<int>(k) == f ? std::abs(d) > tol : d > tol) return false;
  }
  return true;
}

Result<GrindResult> run(const RockMesh& m, int c, const GrindParams& params,
                        std::vector<std::uint8_t>& labels) {
  std::vector<std::byte> block(grind_planes_scratch_bytes(m.tris.size()));
  Arena arena(block);
  labels.assign(m.tris.size(), 0);
  return find_grind_planes(m.cloud.xyz, m.tris, kView.centre(), c, params, arena, labels);
}

TEST(GrindPlanes, ThreeVisibleFacesOfARidgeRock) {
  const RockMesh& m = rock_mesh(0.0);
  const test::Rock rock = test::ridge_rock();
  std::vector<std::uint8_t> labels;
  auto r = run(m, 3, GrindParams{}, labels);
  ASSERT_TRUE(r.ok()) << r.error().message;
  ASSERT_EQ(r->accepted, 3);
  EXPECT_TRUE(r->converged);
  int seen[8] = {};
  for (int k = 0; k < r->accepted; ++k) {
    const GrindPlane& p = r->planes[k];
    const int f = face_of(rock, p);
    ++seen[f];
    EXPECT_LT(angle_deg(p.normal, rock.faces[static_cast<std::size_t>(f)].n), 0.05)
        << "plane " << k;
    EXPECT_TRUE(on_face(rock, f, p.centroid_mm, 0.01)) << "plane " << k;
    EXPECT_LT(p.rms_mm, 0.01);
    EXPECT_GT(p.triangles, 100u);
    if (k > 0) {
      EXPECT_GE(r->planes[k - 1].area_mm2, p.area_mm2);  // ranked by area
    }
  }
  EXPECT_EQ(seen[0], 1);  // roof +x
  EXPECT_EQ(seen[1], 1);  // roof -x
  EXPECT_EQ(seen[5], 1);  // front wall (-y)
  // Labels name the ranked candidate each supporting triangle belongs to.
  std::size_t labelled[kMaxClasses] = {};
  for (auto l : labels)
    if (l != 0xFF) {
      ASSERT_LT(l, r->count);
      ++labelled[l];
    }
  for (int k = 0; k < r->count; ++k) EXPECT_EQ(labelled[k], r->planes[k].triangles);
  // The extra classes (cluster_count(3) = 6) were merged into faces or left
  // as small rejected candidates.
  EXPECT_EQ(cluster_count(3), 6);
  for (int k = 3; k < r->count; ++k) EXPECT_NE(r->planes[k].verdict, PlaneVerdict::accepted);
}

TEST(GrindPlanes, NoisyMeshStillMeetsTheAccuracyTargets) {
  const RockMesh& m = rock_mesh(0.3, 5);
  const test::Rock rock = test::ridge_rock();
  std::vector<std::uint8_t> labels;
  auto r = run(m, 3, GrindParams{}, labels);
  ASSERT_TRUE(r.ok()) << r.error().message;
  ASSERT_EQ(r->accepted, 3);
  for (int k = 0; k < 3; ++k) {
    const GrindPlane& p = r->planes[k];
    const int f = face_of(rock, p);
    EXPECT_LT(angle_deg(p.normal, rock.faces[static_cast<std::size_t>(f)].n), 0.5) << "plane " << k;
    EXPECT_TRUE(on_face(rock, f, p.centroid_mm, 1.0)) << "plane " << k;
  }
}

TEST(GrindPlanes, RejectionsCarryTheirReason) {
  const RockMesh& m = rock_mesh(0.0);
  std::vector<std::uint8_t> labels;
  GrindParams p;
  p.max_view_angle_deg = 45;  // the front wall is seen at ~40 degrees, the roof at ~53
  auto r = run(m, 3, p, labels);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r->accepted, 1);
  EXPECT_LT(r->planes[0].view_angle_deg, 45);
  int roof = 0;  // the two large roof facets (small leftovers may face away too)
  for (int k = 1; k < r->count; ++k)
    if (r->planes[k].area_mm2 > 1000) {
      EXPECT_EQ(r->planes[k].verdict, PlaneVerdict::faces_away);
      ++roof;
    }
  EXPECT_EQ(roof, 2);
  p = {};
  p.grinder_diameter_mm = 200;  // bigger than the rock
  r = run(m, 3, p, labels);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r->accepted, 0);
  for (int k = 0; k < r->count; ++k) EXPECT_EQ(r->planes[k].verdict, PlaneVerdict::too_small);
  EXPECT_STREQ(verdict_name(PlaneVerdict::too_small), "smaller than the grinder footprint");
}

TEST(GrindPlanes, FewerWantedThanQualifyKeepsTheLargest) {
  const RockMesh& m = rock_mesh(0.0);
  std::vector<std::uint8_t> labels;
  auto three = run(m, 3, GrindParams{}, labels);
  ASSERT_TRUE(three.ok());
  auto two = run(m, 2, GrindParams{}, labels);
  ASSERT_TRUE(two.ok());
  ASSERT_EQ(two->accepted, 2);
  // The same two largest faces, and the third reported as surplus.
  for (int k = 0; k < 2; ++k)
    EXPECT_LT(angle_deg(two->planes[k].normal, three->planes[k].normal), 0.05);
  bool surplus = false;
  for (int k = 2; k < two->count; ++k) surplus |= two->planes[k].verdict == PlaneVerdict::surplus;
  EXPECT_TRUE(surplus);
  auto one = run(m, 1, GrindParams{}, labels);
  ASSERT_TRUE(one.ok());
  EXPECT_EQ(one->accepted, 1);
  EXPECT_LT(angle_deg(one->planes[0].normal, three->planes[0].normal), 0.05);
}

TEST(GrindPlanes, BadInputIsNamed) {
  const RockMesh& m = rock_mesh(0.0);
  std::vector<std::uint8_t> labels;
  auto r = run(m, 0, GrindParams{}, labels);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.code(), Errc::out_of_range);
  EXPECT_NE(std::string(r.error().message).find("c = 0"), std::string::npos);
  EXPECT_EQ(run(m, 9, GrindParams{}, labels).code(), Errc::out_of_range);
  RockMesh few = m;
  few.tris.resize(4);
  r = run(few, 2, GrindParams{}, labels);
  EXPECT_EQ(r.code(), Errc::degenerate);
  GrindParams p;
  p.max_rms_mm = -1;
  EXPECT_EQ(run(m, 2, p, labels).code(), Errc::invalid_argument);
}

TEST(GrindPlanes, NoHeap) {
  const RockMesh& m = rock_mesh(0.3, 5);
  std::vector<std::byte> block(grind_planes_scratch_bytes(m.tris.size()));
  Arena arena(block);
  std::vector<std::uint8_t> labels(m.tris.size());
  test::HeapScope scope;
  auto r = find_grind_planes(m.cloud.xyz, m.tris, kView.centre(), 3, GrindParams{}, arena, labels);
  EXPECT_EQ(scope.allocations(), 0u);
  EXPECT_TRUE(r.ok());
  EXPECT_EQ(arena.used(), 0u);
}

}  // namespace
}  // namespace petra
