// Rock/ground segmentation by 3-D clustering (docs/method.md 2a), over a scalar type
// S (double or Fixed<F>):
//   1. seed plane by MSAC: a bounded number of triples drawn by a fixed-seed
//      generator from the points of the ROI's border band (a rock is
//      surrounded by ground), each plane scored on a regular sample by
//      sum min(d^2, T^2), a point more than T below the plane costing
//      below_cost * T^2 (nothing lies under the ground, so a rock face that
//      has the ground behind it loses); T = inlier_sigmas * sigma, where
//      sigma^2 = sigma_Z^2 + roughness^2 and sigma_Z = r^2 sigma_d / (f B)
//      at the sample's mean range r (stereo depth noise, StereoNoise);
//   2. signed distance of every point to the plane (normal towards the
//      cameras, so rock is positive) and k-means with k = 2 on it: ground
//      centre starts at 0, rock centre at the clicked point's distance if a
//      click is given, else at the 98th percentile of the distances;
//   3. total-least-squares refit of the ground cluster, |(A, B, C)| = 1,
//      trimmed to the MSAC inlier band T at first, then to 3 RMS of the
//      previous fit (the foot of the rock falls in the ground cluster);
//   4. repeat 2-3 until |(A,B,C,D) - (A',B',C',D')| < epsilon; the loop
//      runs on a regular sample of at most kSegmentSamples points (each pass
//      costs per point), then one k-means and refit on every point.
// Final labels: ground within max(3 RMS, 2 mm) of the plane, rock above
// (never more than the k-means midpoint). Then the result is checked: the rock must stand out (its
// cluster centre at least min_rock_height_mm and min_rock_height_rms ground RMS above the plane),
// the ground must be a plane as rough as the noise model says (RMS <= max_rms_sigmas * sigma), a
// real share of the points, with almost nothing more than T below it, and hold most of the ROI's
// border band. A failed check sets *failure (GroundFailure) so the caller can segment from the
// click instead (click_region). Inputs: positions (world, mm) and rectified pixels of the cloud,
// the ROI and optional click in rectified pixels, the left camera centre (world, mm), the rig's
// depth noise. Output: labels into a caller span (one per point) and the ground plane. No heap, no
// scratch: every pass streams over the caller's arrays.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "algo/core/image_view.hpp"
#include "algo/core/result.hpp"
#include "algo/mesh/cloud.hpp"
#include "algo/surface/fixed_point.hpp"
#include "algo/surface/plane_fit.hpp"
#include "algo/surface/plane_uncertainty.hpp"

namespace petra {

// The iteration runs on a regular sample of at most this many points; the
// final labels and plane use every point (see ground_segment_impl.hpp).
inline constexpr std::size_t kSegmentSamples = 4096;

struct GroundParams {
  double epsilon = 1e-4;                            // plane-vector change that ends the iteration
  int max_iterations = 50;                          // outer (refit) iterations
  int max_kmeans_passes = 50;                       // inner k-means passes per iteration
  double min_rock_height_mm = 3.0;                  // rock cluster centre above the plane
  double min_rock_height_rms = 4.0;                 // ... and above this many ground RMS
  double sigma_disparity_px = kDisparitySigmaPx;    // matching noise of the disparity (sigma_d)
  double terrain_roughness_mm = 2.0;                // RMS relief of natural ground about its plane
  double inlier_sigmas = 2.5;                       // MSAC inlier band T, in sigma
  double max_rms_sigmas = 2.0;                      // ground RMS limit, in sigma
  double below_cost = 2.0;                          // MSAC cost of a point under the plane, in T^2
  int msac_iterations = 256;                        // triples tried (bounded, deterministic)
  std::uint64_t msac_seed = 0x9E3779B97F4A7C15ull;  // fixed: same input, same plane
  double min_ground_fraction = 0.1;                 // of all points
  double max_below_fraction = 0.05;  // points deeper than min_rock_height_mm below the ground
  double min_trim_band_mm = 0.5;     // floor of the refit's band (3 RMS of the last fit)
  double ground_band_rms = 3.0;      // final labels: ground within this many RMS of the plane
  double min_ground_band_mm = 2.0;   // ... and at least this far
  double min_border_ground = 0.5;    // share of the ROI border band that is ground
  double border_band = 0.08;         // band width as a fraction of min(w, h)
  int click_radius_px = 3;           // a click needs a 3-D point this close
  std::size_t min_points = 30;
};

// The rig's depth noise: sigma_Z = r^2 sigma_d / (focal_px * baseline_mm).
// Zero (unknown rig): the terrain roughness alone sets the tolerance.
struct StereoNoise {
  double focal_px = 0;
  double baseline_mm = 0;
};

// Why no ground was accepted (set when segment_ground fails on the ground).
enum class GroundFailure : std::uint8_t {
  none = 0,
  no_ground,        // no plane holds the ROI's border as ground would
  click_on_ground,  // the click lies on the ground plane
};

struct ClickPx {
  bool present = false;
  int u = 0;  // rectified left pixel
  int v = 0;
};

template <class S>
struct GroundResultT {
  PlaneT<S> plane;        // normal towards the cameras: rock has positive distance
  S rms_mm{};             // of the ground cluster about the plane
  double sigma_mm = 0;    // expected ground scatter: sqrt(sigma_Z^2 + roughness^2)
  double sigma_z_mm = 0;  // stereo depth noise at the ROI's mean range
  S rock_centre_mm{};
  std::size_t ground_points = 0;
  std::size_t rock_points = 0;
  int iterations = 0;
  bool converged = false;
  std::size_t seed[3] = {0, 0, 0};  // indices of the MSAC seed triple
  std::size_t click_point = 0;      // index of the clicked point (if any)
};

Status validate(const GroundParams& p);

template <class S>
Result<GroundResultT<S>> segment_ground(std::span<const Vec3T<S>> xyz_mm,
                                        std::span<const PixelPos> pixels, const Rect& roi,
                                        const ClickPx& click, const Vec3T<S>& camera_centre_mm,
                                        const GroundParams& params, std::span<PointClass> labels,
                                        const StereoNoise& noise = {},
                                        GroundFailure* failure = nullptr);

extern template Result<GroundResultT<double>> segment_ground<double>(
    std::span<const Vec3T<double>>, std::span<const PixelPos>, const Rect&, const ClickPx&,
    const Vec3T<double>&, const GroundParams&, std::span<PointClass>, const StereoNoise&,
    GroundFailure*);

}  // namespace petra

#include "algo/surface/ground_segment_impl.hpp"
