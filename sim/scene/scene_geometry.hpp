// Exact geometric facts about a scene, computed from the polyhedron rather
// than from rendered pixels: which facets both cameras see, the rock's
// outline, and the ground region its shadow covers.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "sim/scene/polygon3.hpp"
#include "sim/scene/scene.hpp"

namespace petra::sim {

// A rock facet seen by both cameras: its part above the ground.
struct VisibleFacet {
  int face = 0;  // index into rock.faces
  Eigen::Vector3d normal;
  Polygon3 polygon;  // exposed polygon, counter-clockwise seen from outside
  Eigen::Vector3d centroid;
  double area_mm2 = 0;
  bool grind_face = false;
};

// Smallest exposed area listed as a facet (slivers below it are left out).
inline constexpr double kMinFacetAreaMm2 = 10.0;

// True when the face's plane is turned toward a camera at `centre`.
bool faces_point(const RockFace& face, const Eigen::Vector3d& centre);

// Facets front-facing to both cameras with at least kMinFacetAreaMm2 above
// the ground, largest first (ties by face index).
std::vector<VisibleFacet> visible_facets(const Scene& scene);
// The same for any rock of the scene (rock_at()).
std::vector<VisibleFacet> visible_facets(const Scene& scene, const ConvexRock& rock);

// Points along every edge of the rock's exposed surface (per_edge per edge).
std::vector<Eigen::Vector3d> rock_outline_points(const ConvexRock& rock, int per_edge);

// Convex hull, on the ground (z = 0), of the rock's footprint and its cast
// shadow for a sun along sun_dir (counter-clockwise seen from above).
Polygon3 shadow_region(const ConvexRock& rock, const Eigen::Vector3d& sun_dir);

// Points along a closed polygon's edges (per_edge per edge).
std::vector<Eigen::Vector3d> polygon_edge_points(const Polygon3& poly, int per_edge);

}  // namespace petra::sim
