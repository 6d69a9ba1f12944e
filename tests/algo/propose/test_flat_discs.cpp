// The grinder-disc search over a rock's faces that the kept planes leave
// (algo/propose/flat_discs): on a ray-cast ridge rock (exact disparity) the
// chain asked for c = 1 explains one face; the search, on the same run's
// mesh, finds the rock's other flat faces by the tool's disc, without the
// clustering, each on a true face, none the explained one, qualified by the
// chain's checks; no heap, within the further pass's bytes; nothing on
// another rock's cells; its parameters checked.
#include "algo/propose/flat_discs.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "tests/algo/propose/ridge_run.hpp"
#include "tests/support/heap_counter.hpp"

namespace petra {
namespace {

TEST(FlatDiscs, FindTheFacesTheKeptPlanesLeaveByTheToolsDisc) {
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
  // The search fits where the further pass's grind step did.
  const std::size_t t = r->mesh.size();
  EXPECT_LE(flat_discs_bytes(t, FlatDiscParams{}.max_seeds), t + 1 + grind_planes_on_mesh_bytes(t));

  const std::uint8_t map[1] = {3};  // one cell over the whole ROI: rock 3
  const RockOnMap on_rock{map, 1, 4096, 3};
  const bool explained[kMaxClasses] = {true};  // plane 0's patch
  const FlatDiscParams discs;
  Result<GrindResult> f = Error::make(Errc::not_ready, "not run");
  {
    const test::HeapScope heap;
    f = flat_discs(rig, pair, params, *r, on_rock, explained, {&first, 1}, discs, nullptr, arena);
    EXPECT_EQ(heap.allocations(), 0u);
  }
  ASSERT_TRUE(f.ok()) << f.error().message;
  ASSERT_GE(f->accepted, 1) << "the ridge rock shows more than one flat face";
  for (int k = 0; k < f->accepted; ++k) {
    const GrindPlane& p = f->planes[k];
    const auto [face, deg] = test::nearest_face(rock, p.normal);
    EXPECT_LT(deg, 1.0) << "disc plane " << k << " rms " << p.rms_mm << " fp " << p.footprint_rms_mm
                        << " area " << p.area_mm2;
    EXPECT_NE(face, first_face) << "disc plane " << k << " is the explained face";
    EXPECT_FALSE(same_face(p, first, params.grind)) << "disc plane " << k;
    EXPECT_LE(p.footprint_rms_mm, discs.max_footprint_rms_mm);
    for (int j = 0; j < k; ++j) EXPECT_FALSE(same_face(p, f->planes[j], params.grind));
  }
  // Another rock's cells: nothing of this rock is taken.
  const RockOnMap elsewhere{map, 1, 4096, 2};
  auto none = flat_discs(rig, pair, params, *r, elsewhere, explained, {}, discs, nullptr, arena);
  ASSERT_TRUE(none.ok()) << none.error().message;
  EXPECT_EQ(none->count, 0);
}

TEST(FlatDiscs, ParametersChecked) {
  EXPECT_TRUE(validate(FlatDiscParams{}).ok());
  FlatDiscParams p;
  p.max_seeds = 0;
  EXPECT_FALSE(validate(p).ok());
  p = FlatDiscParams{};
  p.max_footprint_rms_mm = 0;
  EXPECT_FALSE(validate(p).ok());
  p = FlatDiscParams{};
  p.min_discs = 0;
  EXPECT_FALSE(validate(p).ok());
}

}  // namespace
}  // namespace petra
