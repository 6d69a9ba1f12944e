// Rock/ground segmentation by 3-D clustering (SEED.md 2a), over a scalar type
// S (double or Fixed<F>):
//   1. seed plane through three ground points near the ROI's bottom corners:
//      the valid points nearest the bottom-left and bottom-right corners, and
//      the nearest to a point a quarter of the ROI height above whichever
//      bottom corner gives the larger triangle (three points on one rectified
//      row are collinear in 3-D on flat ground, so one must come from higher);
//   2. signed distance of every point to the plane (normal towards the
//      cameras, so rock is positive) and k-means with k = 2 on it: ground
//      centre starts at 0, rock centre at the clicked point's distance if a
//      click is given, else at the 98th percentile of the distances (the
//      largest would let a few far mismatches seed the rock cluster);
//   3. total-least-squares refit of the ground cluster, |(A, B, C)| = 1
//      (Petra adds: trimmed to the points within 3 RMS of the previous fit,
//      because k-means on distance puts the foot of the rock in the ground
//      cluster and it would tilt the plane by a fraction of a degree);
//   4. repeat 2-3 until |(A,B,C,D) - (A',B',C',D')| < epsilon; the loop
//      runs on a regular sample of at most kSegmentSamples points (each pass
//      costs per point), then one k-means and refit on every point.
// Final labels: ground within max(3 RMS, 2 mm) of the plane, rock above
// (never more than the k-means midpoint). Then the result is checked: the rock must stand out (its
// cluster centre at least min_rock_height_mm above the plane), the ground must be a plane (RMS <=
// max_ground_rms_mm), a real share of the points, with almost nothing below it, and hold most of
// the ROI's border band (a rock is surrounded by ground). Inputs: positions (world, mm) and
// rectified pixels of the cloud, the ROI and optional click in rectified pixels, the left camera
// centre (world, mm). Output: labels into a caller span (one per point) and the ground plane. No
// heap, no scratch: every pass streams over the caller's arrays.
#pragma once

#include <cstddef>
#include <span>

#include "algo/cloud.hpp"
#include "algo/core/image_view.hpp"
#include "algo/core/result.hpp"
#include "algo/fixed_point.hpp"
#include "algo/plane_fit.hpp"

namespace petra {

// The iteration runs on a regular sample of at most this many points; the
// final labels and plane use every point (see ground_segment_impl.hpp).
inline constexpr std::size_t kSegmentSamples = 4096;

struct GroundParams {
  double epsilon = 1e-4;             // plane-vector change that ends the iteration
  int max_iterations = 50;           // outer (refit) iterations
  int max_kmeans_passes = 50;        // inner k-means passes per iteration
  double min_rock_height_mm = 3.0;   // rock cluster centre above the plane
  double max_ground_rms_mm = 1.5;    // ground cluster flatness (trimmed fit)
  double min_ground_fraction = 0.1;  // of all points
  double max_below_fraction = 0.05;  // points deeper than min_rock_height_mm below the ground
  double min_trim_band_mm = 0.5;     // floor of the refit's band (3 RMS of the last fit)
  double ground_band_rms = 3.0;      // final labels: ground within this many RMS of the plane
  double min_ground_band_mm = 2.0;   // ... and at least this far
  double min_border_ground = 0.5;    // share of the ROI border band that is ground
  double border_band = 0.08;         // band width as a fraction of min(w, h)
  int click_radius_px = 3;           // a click needs a 3-D point this close
  std::size_t min_points = 30;
};

struct ClickPx {
  bool present = false;
  int u = 0;  // rectified left pixel
  int v = 0;
};

template <class S>
struct GroundResultT {
  PlaneT<S> plane;  // normal towards the cameras: rock has positive distance
  S rms_mm{};       // of the ground cluster about the plane
  S rock_centre_mm{};
  std::size_t ground_points = 0;
  std::size_t rock_points = 0;
  int iterations = 0;
  bool converged = false;
  std::size_t seed[3] = {0, 0, 0};  // indices of the three seed points
  std::size_t click_point = 0;      // index of the clicked point (if any)
};

Status validate(const GroundParams& p);

template <class S>
Result<GroundResultT<S>> segment_ground(std::span<const Vec3T<S>> xyz_mm,
                                        std::span<const PixelPos> pixels, const Rect& roi,
                                        const ClickPx& click, const Vec3T<S>& camera_centre_mm,
                                        const GroundParams& params, std::span<PointClass> labels);

extern template Result<GroundResultT<double>> segment_ground<double>(
    std::span<const Vec3T<double>>, std::span<const PixelPos>, const Rect&, const ClickPx&,
    const Vec3T<double>&, const GroundParams&, std::span<PointClass>);

}  // namespace petra

#include "algo/ground_segment_impl.hpp"
