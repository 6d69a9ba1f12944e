// The further pass over a rock's faces that the chain's planes leave
// (algo/propose/further_planes): on a ray-cast ridge rock (exact disparity)
// the chain asked for c = 1 explains one face; the pass, on the same run's
// mesh, finds the rock's other flat faces with the chain's own checks, none of
// them the explained face, each on a true face; only the rock's own cells of
// detection's map are taken. And how the proposer orders a rock's candidates
// (one plane per face, a surplus plane offered as accepted, rough patches
// past the chain's own planes dropped), and which planes lie mostly on the rock.
#include "algo/propose/further_planes.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "algo/propose/proposer.hpp"
#include "tests/algo/propose/ridge_run.hpp"
#include "tests/support/heap_counter.hpp"

namespace petra {
namespace {

TEST(FurtherPlanes, FindTheFacesTheChainsPlanesLeaveOnTheRocksOwnCells) {
  test::RidgeRun ridge;
  auto r = ridge.run(1);  // the chain explains one face
  ASSERT_TRUE(r.ok()) << r.error().message;
  ASSERT_EQ(r->planes.accepted, 1);
  const StereoRig& rig = ridge.rig;
  const RectifiedPair& pair = ridge.pair;
  const test::Rock& rock = ridge.rock;
  const ReconstructionParams& params = ridge.params;
  Arena& arena = ridge.arena;
  const GrindPlane& first = r->planes.planes[0];
  const int first_face = test::nearest_face(rock, first.normal).first;

  const std::uint8_t map[1] = {3};  // one cell over the whole ROI: rock 3
  const RockOnMap on_rock{map, 1, 4096, 3};
  const bool explained[kMaxClasses] = {true};  // plane 0's triangles
  Result<GrindResult> f = Error::make(Errc::not_ready, "not run");
  {
    const test::HeapScope heap;
    f = further_planes(rig, pair, params, *r, on_rock, explained, 2, nullptr, arena);
    EXPECT_EQ(heap.allocations(), 0u);
  }
  ASSERT_TRUE(f.ok()) << f.error().message;
  ASSERT_GE(f->accepted, 1) << "the ridge rock shows more than one flat face";
  for (int k = 0; k < f->accepted; ++k) {
    const GrindPlane& p = f->planes[k];
    const auto [face, deg] = test::nearest_face(rock, p.normal);
    EXPECT_LT(deg, 1.0) << "further plane " << k;
    EXPECT_NE(face, first_face) << "further plane " << k << " is the explained face";
    EXPECT_FALSE(same_face(p, first, params.grind)) << "further plane " << k;
  }
  // Another rock's cells: nothing of this rock is taken.
  const RockOnMap elsewhere{map, 1, 4096, 2};
  auto none = further_planes(rig, pair, params, *r, elsewhere, explained, 2, nullptr, arena);
  ASSERT_TRUE(none.ok()) << none.error().message;
  EXPECT_EQ(none->count, 0);
}

GrindPlane plane(const Eigen::Vector3d& n, const Eigen::Vector3d& c, PlaneVerdict v,
                 double rms_mm) {
  GrindPlane p;
  p.normal = n.normalized();
  p.centroid_mm = c;
  p.verdict = v;
  p.rms_mm = rms_mm;
  return p;
}

TEST(FurtherPlanes, CandidatesOnePerFaceSurplusOfferedRoughExtrasDropped) {
  const GrindParams grind;
  PlaneCandidates c;
  const GrindPlane top = plane({0, 0, 1}, {0, 0, 50}, PlaneVerdict::accepted, 1.5);
  c.add(top, grind);
  // The same face (2 deg, 1 mm off): not added again.
  c.add(plane({0, std::sin(2 * M_PI / 180), std::cos(2 * M_PI / 180)}, {10, 0, 51},
              PlaneVerdict::accepted, 0.5),
        grind);
  EXPECT_EQ(c.count, 1);
  // Parallel but 10 mm lower: another face.
  c.add(plane({0, 0, 1}, {0, 0, 40}, PlaneVerdict::surplus, 0.5), grind);
  c.add(plane({1, 0, 0}, {40, 0, 20}, PlaneVerdict::accepted, 2.5), grind);  // a crease
  ASSERT_EQ(c.count, 3);
  EXPECT_EQ(c.planes[1].verdict, PlaneVerdict::accepted) << "surplus passed every check";
  c.keep_flat(1, grind);  // the chain's own plane stays however rough its patch
  ASSERT_EQ(c.count, 2);
  EXPECT_EQ(c.planes[0].rms_mm, 1.5);
  EXPECT_EQ(c.planes[1].centroid_mm.z(), 40.0);
}

// Plane 0 on rock 1's cells, plane 1 mostly on the ground (no rock), plane 2
// mostly on another rock, plane 3 half and half.
TEST(FurtherPlanes, PlanesMostlyOnTheRock) {
  const std::uint8_t map[4] = {0, 1, kNoRock, kOtherRock};
  std::vector<PixelPos> px;
  std::vector<std::uint8_t> cls;
  auto add = [&](int k, int cell, int n) {
    for (int i = 0; i < n; ++i) {
      px.push_back({static_cast<std::int16_t>(cell * 4 + i % 4), 2});
      cls.push_back(static_cast<std::uint8_t>(kVertexPlane0 + k));
    }
  };
  add(0, 1, 10);
  add(1, 1, 3), add(1, 2, 7);
  add(2, 1, 2), add(2, 3, 5);
  add(3, 1, 4), add(3, 2, 4);
  ReconstructionOutput r;
  r.pixels = px;
  r.vertex_class = cls;
  bool on[kMaxClasses] = {};
  planes_mostly_on(r, RockOnMap{map, 4, 4, 1}, on);
  EXPECT_TRUE(on[0]);
  EXPECT_FALSE(on[1]);
  EXPECT_FALSE(on[2]);
  EXPECT_FALSE(on[3]);
  EXPECT_FALSE(on[4]);  // no vertex
}

}  // namespace
}  // namespace petra
