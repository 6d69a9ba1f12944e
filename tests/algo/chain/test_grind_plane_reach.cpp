#include "algo/chain/grind_plane_reach.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <vector>

#include "tests/support/heap_counter.hpp"

namespace petra {
namespace {

// A flat square face of side 2 h mm in the plane z = 0, a grid of points
// `step` mm apart, two triangles per cell, every triangle plane 0's.
struct FlatFace {
  std::vector<Eigen::Vector3d> xyz;
  std::vector<MeshTriangle> mesh;
  std::vector<std::uint8_t> mesh_class;
  ReconstructionOutput out;
};

void make_flat_face(FlatFace& f, double h = 30.0, double step = 2.0) {
  const int n = static_cast<int>(2 * h / step) + 1;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) f.xyz.emplace_back(-h + i * step, -h + j * step, 0.0);
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i) {
      const std::int32_t a = j * n + i, b = a + 1, c = a + n, d = c + 1;
      f.mesh.push_back(MeshTriangle{{a, b, d}});
      f.mesh.push_back(MeshTriangle{{a, d, c}});
    }
  f.mesh_class.assign(f.mesh.size(), kVertexPlane0);
  f.out.xyz_mm = f.xyz;
  f.out.mesh = f.mesh;
  f.out.mesh_class = f.mesh_class;
  GrindPlane& p = f.out.planes.planes[0];
  p.normal = Eigen::Vector3d::UnitZ();
  p.centroid_mm = Eigen::Vector3d::Zero();
  p.footprint_reach = FootprintReach::most_level;
  p.verdict = PlaneVerdict::accepted;
  f.out.planes.count = 1;
  f.out.planes.accepted = 1;
}

// A reach the test draws: discs whose centre has x beyond `x_min`.
class BeyondX final : public DiscReach {
 public:
  explicit BeyondX(double x_min) : x_min_(x_min) {}
  bool reaches(const Eigen::Vector3d& centre_mm, const Eigen::Vector3d&) const override {
    ++asked;
    return centre_mm.x() > x_min_;
  }
  mutable int asked = 0;

 private:
  double x_min_;
};

const Eigen::Vector3d kCamera(0.0, 0.0, 1000.0);  // above the face's centre

const PlaneMove kStill{true, Eigen::Vector3d::UnitZ(), Eigen::Vector3d::Zero(),
                       Eigen::Vector3d::Zero()};

Result<int> run(FlatFace& f, const PlaneMove& move, const DiscReach& reach) {
  static std::vector<std::byte> block(footprint_again_scratch_bytes(4096) + 4096);
  Arena arena(block);
  const PlaneMove moves[1] = {move};
  test::HeapScope scope;
  auto r = footprints_after_refinement(moves, GrindParams{}, reach, kCamera, f.out, arena);
  EXPECT_EQ(scope.allocations(), 0u);
  EXPECT_LE(arena.high_water(), footprint_again_scratch_bytes(f.mesh.size()));
  return r;
}

TEST(FootprintsAfterRefinement, ADiscTheArmNoLongerReachesIsChosenAgainWhereItDoes) {
  FlatFace f;
  make_flat_face(f);
  const BeyondX reach(12.0);
  auto r = run(f, kStill, reach);
  ASSERT_TRUE(r.ok()) << r.error().message;
  EXPECT_EQ(*r, 1);
  const GrindPlane& p = f.out.planes.planes[0];
  EXPECT_EQ(p.footprint_reach, FootprintReach::moved);
  EXPECT_GT(p.centroid_mm.x(), 12.0);
  EXPECT_LT(p.centroid_mm.x(), 25.0) << "a disc the face covers";
  EXPECT_NEAR(p.centroid_mm.z(), 0.0, 1e-9);
  EXPECT_NEAR(p.footprint_rms_mm, 0.0, 1e-9);
  EXPECT_NEAR(p.footprint_coverage, 1.0, 0.15);
  EXPECT_EQ(p.verdict, PlaneVerdict::accepted) << "the verdict stays the grind step's";
  // Seen from the camera above the face's centre, the moved point is seen aslant.
  EXPECT_NEAR(
      p.view_angle_deg,
      std::atan2(std::hypot(p.centroid_mm.x(), p.centroid_mm.y()), 1000.0 - p.centroid_mm.z()) *
          180.0 / M_PI,
      1e-9);
  EXPECT_GT(p.view_angle_deg, 0.6);
}

TEST(FootprintsAfterRefinement, ADiscStillReachedOrAPlaneNotRefinedIsLeftAlone) {
  FlatFace f;
  make_flat_face(f);
  const BeyondX everywhere(-1e9);
  auto r = run(f, kStill, everywhere);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(*r, 0);
  EXPECT_EQ(everywhere.asked, 1);
  EXPECT_EQ(f.out.planes.planes[0].centroid_mm, Eigen::Vector3d::Zero());

  PlaneMove unrefined = kStill;
  unrefined.refined = false;
  const BeyondX reach(12.0);
  r = run(f, unrefined, reach);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(*r, 0);
  EXPECT_EQ(reach.asked, 0);
  EXPECT_EQ(f.out.planes.planes[0].footprint_reach, FootprintReach::most_level);

  f.out.planes.planes[0].footprint_reach = FootprintReach::not_asked;  // no reach at the grind step
  r = run(f, kStill, reach);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(*r, 0);
  EXPECT_EQ(f.out.planes.planes[0].centroid_mm, Eigen::Vector3d::Zero());

  // Reached at no flat disc along the mesh's normal: listed so, not asked again.
  f.out.planes.planes[0].footprint_reach = FootprintReach::none_reached;
  r = run(f, kStill, reach);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(*r, 0);
  EXPECT_EQ(reach.asked, 0);
  EXPECT_EQ(f.out.planes.planes[0].footprint_reach, FootprintReach::none_reached);
}

TEST(FootprintsAfterRefinement, NoDiscReachedAnyMoreKeepsTheDiscAndSaysSo) {
  FlatFace f;
  make_flat_face(f);
  const BeyondX nowhere(1e9);
  auto r = run(f, kStill, nowhere);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(*r, 1);
  EXPECT_GT(nowhere.asked, 1) << "every flat disc asked";
  EXPECT_EQ(f.out.planes.planes[0].footprint_reach, FootprintReach::none_reached);
  EXPECT_EQ(f.out.planes.planes[0].centroid_mm, Eigen::Vector3d::Zero());
}

TEST(FootprintsAfterRefinement, TheNewDiscMovesWithTheRefinedPlane) {
  // The refinement raised the face's plane by 1 mm and tilted it by 1 deg
  // about y: the new grind point lies on the refined plane (the mesh's disc
  // stood on the mesh's plane), not on the mesh.
  FlatFace f;
  make_flat_face(f);
  const double a = M_PI / 180.0;
  GrindPlane& p = f.out.planes.planes[0];
  p.normal = Eigen::Vector3d(std::sin(a), 0.0, std::cos(a));
  PlaneMove move = kStill;
  move.point_after = Eigen::Vector3d(0, 0, 1);
  p.centroid_mm = move.point_after;
  const BeyondX reach(12.0);
  auto r = run(f, move, reach);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(*r, 1);
  EXPECT_GT(p.centroid_mm.x(), 12.0);
  EXPECT_NEAR(p.normal.dot(p.centroid_mm - move.point_after), 0.0, 1e-9);
  EXPECT_NEAR(p.centroid_mm.z(), 1.0 - std::tan(a) * p.centroid_mm.x(), 0.01);
}

TEST(FootprintsAfterRefinement, AShortArenaIsAnError) {
  FlatFace f;
  make_flat_face(f);
  std::vector<std::byte> block(64);
  Arena arena(block);
  const PlaneMove moves[1] = {kStill};
  const BeyondX reach(12.0);
  auto r = footprints_after_refinement(moves, GrindParams{}, reach, kCamera, f.out, arena);
  EXPECT_FALSE(r.ok());
}

}  // namespace
}  // namespace petra
