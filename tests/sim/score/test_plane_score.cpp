// The scorer on hand-made cases: a box-shaped rock top with two known flat
// facets, and plane sets that are right, flipped, misplaced, too few or too
// many.
#include "sim/score/plane_score.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace petra::sim {
namespace {

// Facet 0: the 40 x 30 mm top of a box at z = 50 (normal +z).
// Facet 1: its 40 x 50 mm front at y = 0 (normal -y).
TruthFile box_truth() {
  TruthFile t;
  t.roi = {100, 100, 200, 150};
  t.planes = 2;
  TruthFacet top;
  top.normal = {0, 0, 1};
  top.polygon_mm = {{0, 0, 50}, {40, 0, 50}, {40, 30, 50}, {0, 30, 50}};
  top.centroid_mm = {20, 15, 50};
  top.visible_area_mm2 = 1200;
  top.grind_face = true;
  TruthFacet front;
  front.normal = {0, -1, 0};
  front.polygon_mm = {{0, 0, 0}, {0, 0, 50}, {40, 0, 50}, {40, 0, 0}};
  front.centroid_mm = {20, 0, 25};
  front.visible_area_mm2 = 2000;
  front.grind_face = true;
  t.facets = {front, top};  // largest first
  t.ground_normal = {0, 0, 1};
  t.ground_d_mm = 0;
  return t;
}

OutputPlane plane(Eigen::Vector3d n, Eigen::Vector3d c) {
  OutputPlane p;
  p.normal = n.normalized();
  p.centroid_mm = c;
  return p;
}

PlanesFile perfect() {
  PlanesFile f;
  f.planes = {plane({0, -1, 0}, {20, 0, 25}), plane({0, 0, 1}, {20, 15, 50})};
  f.ground = GroundPlane{{0, 0, 1}, 0};
  return f;
}

TEST(PlaneScore, PerfectPlanesScoreZero) {
  const PlaneScore s = score_planes(box_truth(), perfect());
  EXPECT_TRUE(s.count_agrees);
  ASSERT_EQ(s.facets.size(), 2u);
  for (const FacetScore& f : s.facets) {
    EXPECT_EQ(f.plane, f.facet);
    EXPECT_NEAR(f.normal_error_deg, 0, 1e-6);
    EXPECT_NEAR(f.centroid_plane_distance_mm, 0, 1e-12);
    EXPECT_TRUE(f.centroid_on_facet);
  }
  EXPECT_TRUE(s.extra_planes.empty());
  ASSERT_TRUE(s.ground.has_value());
  EXPECT_NEAR(s.ground->normal_error_deg, 0, 1e-6);
  EXPECT_NEAR(s.ground->height_error_mm, 0, 1e-12);
}

TEST(PlaneScore, PlanesAreMatchedWhateverTheirRank) {
  PlanesFile f = perfect();
  std::swap(f.planes[0], f.planes[1]);
  const PlaneScore s = score_planes(box_truth(), f);
  EXPECT_EQ(s.facets[0].plane, 1);
  EXPECT_EQ(s.facets[1].plane, 0);
  EXPECT_NEAR(s.facets[0].normal_error_deg, 0, 1e-6);
}

TEST(PlaneScore, AFlippedNormalIsMatchedByPlaceAndReads180Degrees) {
  PlanesFile f = perfect();
  f.planes[1].normal = -f.planes[1].normal;  // the top's normal points into the rock
  const PlaneScore s = score_planes(box_truth(), f);
  EXPECT_EQ(s.facets[1].plane, 1);
  EXPECT_NEAR(s.facets[1].normal_error_deg, 180.0, 1e-6);
  EXPECT_TRUE(s.facets[1].centroid_on_facet);
  EXPECT_EQ(s.facets[0].plane, 0);
}

TEST(PlaneScore, ACentroidOffTheFacetIsMeasured) {
  PlanesFile f = perfect();
  f.planes[1].centroid_mm = {47, 15, 53};  // 7 mm beyond the top's edge, 3 mm above it
  f.planes[1].normal = Eigen::Vector3d(0, std::sin(0.1), std::cos(0.1));
  const PlaneScore s = score_planes(box_truth(), f);
  ASSERT_EQ(s.facets[1].plane, 1);
  EXPECT_FALSE(s.facets[1].centroid_on_facet);
  EXPECT_NEAR(s.facets[1].centroid_outside_mm, 7.0, 1e-12);
  EXPECT_NEAR(s.facets[1].centroid_plane_distance_mm, 3.0, 1e-12);
  EXPECT_NEAR(s.facets[1].normal_error_deg, 0.1 * 180 / M_PI, 1e-9);
}

TEST(PlaneScore, TooFewPlanesLeaveAFacetUnmatched) {
  PlanesFile f = perfect();
  f.planes.erase(f.planes.begin());  // only the top
  const PlaneScore s = score_planes(box_truth(), f);
  EXPECT_FALSE(s.count_agrees);
  EXPECT_EQ(s.output_planes, 1);
  EXPECT_EQ(s.truth_planes, 2);
  EXPECT_EQ(s.facets[0].plane, -1);
  EXPECT_EQ(s.facets[1].plane, 0);
}

TEST(PlaneScore, TooManyPlanesAreListedAsExtra) {
  PlanesFile f = perfect();
  f.planes.insert(f.planes.begin(), plane({1, 0, 0}, {40, 15, 25}));  // a side face, ranked first
  const PlaneScore s = score_planes(box_truth(), f);
  EXPECT_FALSE(s.count_agrees);
  EXPECT_EQ(s.facets[0].plane, 1);
  EXPECT_EQ(s.facets[1].plane, 2);
  ASSERT_EQ(s.extra_planes.size(), 1u);
  EXPECT_EQ(s.extra_planes[0], 0);
}

// A plane on a real face the truth did not design (the box's right side) is
// measured against that face; the designed top it does not lie on is missed,
// not matched 90 degrees off.
TEST(PlaneScore, APlaneOnAnUndesignedFacetIsMeasuredThere) {
  TruthFile t = box_truth();
  TruthFacet side;
  side.normal = {1, 0, 0};
  side.polygon_mm = {{40, 0, 0}, {40, 30, 0}, {40, 30, 50}, {40, 0, 50}};
  side.centroid_mm = {40, 15, 25};
  side.visible_area_mm2 = 1500;
  t.facets.push_back(side);  // past t.planes = 2: not a designed face
  PlanesFile f = perfect();
  f.planes[1] = plane({1, 0, 0.01}, {40, 15, 26});
  const PlaneScore s = score_planes(t, f);
  ASSERT_EQ(s.facets.size(), 2u);
  EXPECT_EQ(s.facets[0].plane, 0);
  EXPECT_EQ(s.facets[1].plane, -1);
  ASSERT_EQ(s.other_facets.size(), 1u);
  EXPECT_EQ(s.other_facets[0].facet, 2);
  EXPECT_EQ(s.other_facets[0].plane, 1);
  EXPECT_LT(s.other_facets[0].normal_error_deg, 1.0);
  EXPECT_TRUE(s.other_facets[0].centroid_on_facet);
  EXPECT_TRUE(s.extra_planes.empty());
  // Flipped, the plane on the top still reads 180 deg there, not a smaller
  // angle on the side.
  f = perfect();
  f.planes[1].normal = -f.planes[1].normal;
  const PlaneScore flipped = score_planes(t, f);
  EXPECT_EQ(flipped.facets[1].plane, 1);
  EXPECT_NEAR(flipped.facets[1].normal_error_deg, 180.0, 1e-6);
  EXPECT_TRUE(flipped.other_facets.empty());
}

TEST(PlaneScore, NoPlanesAtAll) {
  PlanesFile f;
  const PlaneScore s = score_planes(box_truth(), f);
  EXPECT_FALSE(s.count_agrees);
  for (const FacetScore& fs : s.facets) EXPECT_EQ(fs.plane, -1);
  EXPECT_FALSE(s.ground.has_value());
}

TEST(PlaneScore, GroundErrorsIgnoreTheNormalsSign) {
  PlanesFile f = perfect();
  const double a = 2.0 * M_PI / 180;
  f.ground = GroundPlane{{0, -std::sin(a), -std::cos(a)}, 4.0};  // tilted 2 deg, flipped
  const PlaneScore s = score_planes(box_truth(), f);
  ASSERT_TRUE(s.ground.has_value());
  EXPECT_NEAR(s.ground->normal_error_deg, 2.0, 1e-9);
  // Under the facets' mean centroid (20, 7.5, 37.5) -> ground point (20, 7.5, 0).
  EXPECT_NEAR(s.ground->height_error_mm, std::abs(-std::sin(a) * 7.5 + 4.0), 1e-9);
}

}  // namespace
}  // namespace petra::sim
