// Whether the grinder can work a face (grind_planes step 5), from the face's
// patch and its whole-patch plane:
//   1. the footprint: the best disc of the tool's diameter on the patch
//      (algo/surface/grind_footprint) and its own plane;
//   2. the uncertainty of both planes (algo/surface/plane_uncertainty): each patch
//      triangle stands for the pixels it covers, its area across the viewing
//      ray over (R / f)^2 (FaceSample::seen; without it area / ((R / f)^2 / cos)),
//      measured along its viewing ray with the stereo depth noise;
//   3. the reported plane: the face's normal through the disc's centre on
//      the surface (the disc's own plane there); the
//      disc's plane agrees with it when their normals are within
//      agree_sigmas of their combined normal sigma and the disc's centre
//      within agree_sigmas of their combined offset sigma; with
//      report_disc_plane a disc that disagrees gives its own plane
//      (footprint_local: the face curves at the tool's scale);
//   4. the verdict: faces_away, too_small, too_rough, too_uncertain or
//      accepted (grindable), in that order.
// In: the patch's samples, the first `core` of them the ones the face plane
// was fitted on; plane.normal and plane.centroid_mm hold the whole-patch
// plane, area, rms and triangles are set. Out: the plane's footprint, face and
// uncertainty fields, normal, centroid, view angle and verdict.
// Scratch: footprint_scratch_bytes(patch.size()), released. No heap.
#pragma once

#include <span>

#include "algo/core/arena.hpp"
#include "algo/core/result.hpp"
#include "algo/surface/grind_footprint.hpp"
#include "algo/surface/grind_planes.hpp"
#include "algo/surface/plane_uncertainty.hpp"

namespace petra {

Status qualify_plane(std::span<const FaceSample> patch, std::size_t core,
                     const Eigen::Vector3d& camera_mm, const GrindParams& params,
                     const DepthNoise& noise, Arena& scratch, GrindPlane& plane,
                     const DiscReach* reach = nullptr);

}  // namespace petra
