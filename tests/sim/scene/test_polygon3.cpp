#include "sim/scene/polygon3.hpp"

#include <gtest/gtest.h>

namespace petra::sim {
namespace {

// A 10 x 20 rectangle in the plane z = 5, counter-clockwise seen from +z.
Polygon3 rect() {
  return {{0, 0, 5}, {10, 0, 5}, {10, 20, 5}, {0, 20, 5}};
}

TEST(Polygon3, AreaCentroidAndOrientation) {
  EXPECT_DOUBLE_EQ(polygon_area(rect()), 200.0);
  EXPECT_TRUE(polygon_centroid(rect()).isApprox(Eigen::Vector3d(5, 10, 5)));
  EXPECT_GT(polygon_vector_area(rect()).z(), 0);
  const Polygon3 tri = {{0, 0, 0}, {3, 0, 0}, {0, 3, 0}};
  EXPECT_TRUE(polygon_centroid(tri).isApprox(Eigen::Vector3d(1, 1, 0)));
}

TEST(Polygon3, ClipKeepsTheInsideOfTheHalfSpace) {
  const Polygon3 left = clip_polygon(rect(), Eigen::Vector3d(1, 0, 0), 4.0);  // x <= 4
  EXPECT_DOUBLE_EQ(polygon_area(left), 80.0);
  for (const auto& p : left) EXPECT_LE(p.x(), 4.0 + 1e-12);
  EXPECT_TRUE(clip_polygon(rect(), Eigen::Vector3d(1, 0, 0), -1.0).empty());
  EXPECT_EQ(clip_polygon(rect(), Eigen::Vector3d(1, 0, 0), 11.0).size(), 4u);
}

TEST(Polygon3, DistancesToAPolygon) {
  const Eigen::Vector3d n(0, 0, 1);
  EXPECT_DOUBLE_EQ(in_plane_distance_to_polygon(rect(), n, {5, 5, 9}), 0.0);    // above, inside
  EXPECT_DOUBLE_EQ(in_plane_distance_to_polygon(rect(), n, {13, 5, 5}), 3.0);   // beside an edge
  EXPECT_DOUBLE_EQ(in_plane_distance_to_polygon(rect(), n, {13, 24, 5}), 5.0);  // off a corner
  EXPECT_DOUBLE_EQ(distance_to_polygon(rect(), n, {5, 5, 9}), 4.0);
  EXPECT_DOUBLE_EQ(distance_to_polygon(rect(), n, {13, 24, 17}), 13.0);
  // Orientation of the polygon does not matter.
  const Polygon3 ccw = rect();
  const Polygon3 cw(ccw.rbegin(), ccw.rend());
  EXPECT_DOUBLE_EQ(in_plane_distance_to_polygon(cw, n, {5, 5, 5}), 0.0);
  EXPECT_DOUBLE_EQ(in_plane_distance_to_polygon(cw, n, {13, 5, 5}), 3.0);
}

}  // namespace
}  // namespace petra::sim
