// Whether a fitted ground plane is ground by its points' own orientation.
// The ground fit checks distances only. Where the ROI holds nothing but a
// rock's faces (the rock fills the ROI), a plane across two faces' outer
// parts, with the ridge between them above it, passes those checks; but the
// faces' points lean away from that plane by half the ridge's angle, where
// natural ground, relief and pebbles included, mostly faces along its plane.
// Input: smoothed surface normals per point (zero: none), the labels of
// segment_ground and its plane's normal. Output: the share of the ground
// points with a normal that lean at most max_lean_deg from the plane's
// (points without a normal are not counted). No heap, no scratch.
#pragma once

#include <Eigen/Core>
#include <span>

#include "algo/core/result.hpp"
#include "algo/mesh/cloud.hpp"

namespace petra {

struct GroundNormalParams {
  // Set on the realistic set (docs/reconstruction.md): ground 0.73-0.95 of its
  // points within 20 deg, two faces of a rock filling the ROI 0.33-0.36.
  double max_lean_deg = 20.0;  // a ground point's normal against the plane's
  double min_share = 0.55;     // of the ground points, leaning at most that
};

struct GroundNormalShare {
  std::size_t counted = 0;  // ground points with a normal
  double share = 1.0;       // of them, leaning at most max_lean_deg (1 when none counted)
};

// max_lean_deg in (0, 90), min_share in [0, 1].
Status validate(const GroundNormalParams& p);

GroundNormalShare ground_normal_share(std::span<const Eigen::Vector3d> normals,
                                      std::span<const PointClass> labels,
                                      const Eigen::Vector3d& plane_normal,
                                      const GroundNormalParams& params);

}  // namespace petra
