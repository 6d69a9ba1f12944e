// Planar convex polygons in 3-D (mm): clipping by a half-space, area,
// centroid, and where a point lies relative to one. Used to build the rock,
// to describe its facets in truth.json, and by the scorer.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace petra::sim {

using Polygon3 = std::vector<Eigen::Vector3d>;

// The part of a convex polygon where n.x <= d (vertex order is kept).
Polygon3 clip_polygon(const Polygon3& poly, const Eigen::Vector3d& n, double d);

// Vector area: 0.5 * sum of cross products; its norm is the area and its
// direction the polygon's normal for counter-clockwise order.
Eigen::Vector3d polygon_vector_area(const Polygon3& poly);
double polygon_area(const Polygon3& poly);
// Area centroid (the vertex mean for a degenerate polygon).
Eigen::Vector3d polygon_centroid(const Polygon3& poly);

// Distance, within the polygon's plane, from the projection of p onto that
// plane to the convex polygon: 0 when the projection lies inside.
// `normal` is the polygon's unit normal.
double in_plane_distance_to_polygon(const Polygon3& poly, const Eigen::Vector3d& normal,
                                    const Eigen::Vector3d& p);
// 3-D distance from p to the polygon (as a filled surface).
double distance_to_polygon(const Polygon3& poly, const Eigen::Vector3d& normal,
                           const Eigen::Vector3d& p);

// Points on a convex polygon about step_mm apart (fan triangles, barycentric
// grid; shared edges give repeated points).
std::vector<Eigen::Vector3d> polygon_samples(const Polygon3& poly, double step_mm);

}  // namespace petra::sim
