// Scores grind planes (planes.json) against the simulator's truth. The
// truth's first `planes` facets are the designed flat faces; the others are
// the rest of the rock's visible facets. Every output plane is matched to at
// most one facet, designed or not: the matching minimises, over all
// one-to-one assignments that match as many planes as possible, the sum of
//   distance from the plane's centroid to the facet polygon (mm)
//   + 1 mm per degree between the normals (their sign ignored),
// so a plane is matched by where it is even when its normal is wrong, and a
// plane on a real face the truth did not design is measured against that
// face (not forced onto a designed face it does not lie on).
#pragma once

#include <optional>
#include <vector>

#include "sim/score/planes_file.hpp"
#include "sim/score/truth_file.hpp"

namespace petra::sim {

inline constexpr double kMatchMmPerDeg = 1.0;

// Angle between two directions (deg); neither need be of unit length.
double angle_between_deg(const Eigen::Vector3d& a, const Eigen::Vector3d& b);

struct FacetScore {
  int facet = 0;                          // index into truth facets
  int plane = -1;                         // matched output plane, -1 when none is left
  double normal_error_deg = 0;            // angle between the unit normals (180 = flipped)
  double centroid_plane_distance_mm = 0;  // |n . (centroid - facet point)|
  double centroid_outside_mm = 0;         // in-plane distance from the facet polygon (0 = on it)
  bool centroid_on_facet = false;         // centroid's projection lies on the facet polygon
};

struct GroundScore {
  double normal_error_deg = 0;  // between the plane normals, orientation ignored
  double height_error_mm = 0;   // output plane's distance from the truth ground below the rock
};

struct PlaneScore {
  int truth_planes = 0;
  int output_planes = 0;
  bool count_agrees = false;
  std::vector<FacetScore> facets;        // one per designed facet, in truth order
  std::vector<FacetScore> other_facets;  // planes on the other visible facets, by facet
  std::vector<int> extra_planes;         // output planes matched to no facet
  std::optional<GroundScore> ground;
};

PlaneScore score_planes(const TruthFile& truth, const PlanesFile& planes);

}  // namespace petra::sim
