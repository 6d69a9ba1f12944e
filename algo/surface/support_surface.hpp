// Whether a grind plane of a rock grown from the click (click_region) is the
// surface the rock stands on. The growth stops at concave edges judged per
// mesh edge; a boulder bedded in sloped sand meets it in a gradual concave bend
// (tens of edges, each under the limit, the smoothed normals scattered by the
// matcher's staircase more than the bend turns per edge), so the region can run
// onto the sand and a plane be found there. A rock is convex at the scale of
// its faces: it lies behind each face's plane, the clicked point too. The
// ground it stands on has the rock rising in front of it. The test, per plane
// (its whole patch's plane, area A, radius r = sqrt(A / pi), RMS): the clicked
// point more than click_radii r in front of it, and of the rock points within
// radius_factor r of its centroid along the plane, more than max_share more
// than margin_rms RMS in front. Then the rock points within that radius on or
// behind the plane (up to the margin in front) are the ground's.
// Inputs: positions (mm), labels (rock = the region). No heap, no scratch.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <span>

#include "algo/core/result.hpp"
#include "algo/mesh/cloud.hpp"

namespace petra {

struct SupportParams {
  // Measured (docs/reconstruction.md, "A real Mars pair"): share in front, the
  // Mars sand plane 0.62 (0.65 with the tighter ROI), the boulder's faces 0.01-0.12,
  // the realistic set's click scenes 0.00-0.01, Rocks1 0.00-0.09; the click in
  // front of the sand plane 1.7 r (2.1 r), of every other plane at most 0.7 r
  // (a band along the boulder's rim, 0.63 in front; before the closed-form
  // triangulation Rocks1's green slab under the grey rock, 0.49 and 0.37 r).
  double radius_factor = 3.0;  // of the plane's own radius r = sqrt(area / pi)
  double margin_rms = 3.0;     // in front: more than this many RMS of the plane
  double max_share = 0.25;     // of the rock near the plane in front: above, it is the support
  double click_radii = 1.0;    // the click at least this many r in front of the support
};

// The plane as the test sees it: its whole patch's plane and size.
struct SupportPlane {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  // unit, out of the rock
  Eigen::Vector3d centroid_mm = Eigen::Vector3d::Zero();
  double area_mm2 = 0;
  double rms_mm = 0;
};

struct RockInFront {
  std::size_t near = 0;        // rock points within the radius along the plane
  std::size_t in_front = 0;    // of them, more than the margin in front
  double click_height_mm = 0;  // the clicked point in front of the plane
  double plane_radius_mm = 0;  // r = sqrt(area / pi)
  double share() const {
    return near == 0 ? 0.0 : static_cast<double>(in_front) / static_cast<double>(near);
  }
};

// radius_factor, margin_rms and click_radii > 0, max_share in (0, 1).
Status validate(const SupportParams& p);

// click: the clicked point's index (the region's seed).
RockInFront rock_in_front(std::span<const Eigen::Vector3d> xyz_mm,
                          std::span<const PointClass> labels, std::size_t click,
                          const SupportPlane& plane, const SupportParams& params);

bool stands_on(const RockInFront& r, const SupportParams& params);

// The rock points within the radius on or behind the plane become ground;
// returns how many.
std::size_t drop_support(std::span<const Eigen::Vector3d> xyz_mm, std::span<PointClass> labels,
                         const SupportPlane& plane, const SupportParams& params);

}  // namespace petra
