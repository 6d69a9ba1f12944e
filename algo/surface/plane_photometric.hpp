// Photometric refinement of a face's disparity plane. A plane is affine in
// rectified disparity, d(u, v) = a (u - u0) + b (v - v0) + c; Gauss-Newton
// on (a, b, c), a gain/offset of the right image and a relative blur of the
// left image (wx, wy) minimises
//   sum over the face's left pixels of (L + wx Lxx + wy Lyy - g R(u - d, v) - o)^2
// (Lxx, Lyy: second differences of L at (u, v)) with linear sampling of R.
// The blur term: a face seen more obliquely by one camera shows it less
// detail (a pixel integrates a larger footprint); without it the plane
// leans to trade slope against the lost detail. Every pixel of the face votes for one plane:
// on a steep, weakly textured face a matcher's per-pixel disparity is a
// staircase of whole-pixel steps (the scanline DP lays it out as
// fronto-parallel runs with false occlusions between them) whose plane leans
// by degrees; the face's pixels together fix it far better.
// Residuals beyond trim_sigma times the last RMS are left out (occlusions,
// pixels of a neighbouring face). The refined plane is kept only when the
// cost fell and it stays within max_shift_px of the initial one at the
// face's bounding box corners (a wrong basin is refused, not followed).
// Inputs:  rectified left/right images (the right valid inside right_valid),
//          the face's rectified left pixels, the initial plane (px).
// Output:  the fit (plane, accepted, iterations, pixels, truncated RMS gray before/after).
// Memory:  none (no scratch, no heap). Time: pixels x iterations.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "algo/core/image_view.hpp"
#include "algo/core/result.hpp"
#include "algo/mesh/cloud.hpp"

namespace petra {

struct PhotometricPlaneParams {
  bool enabled = true;
  int max_iterations = 10;    // 1..50
  double trim_sigma = 2.5;    // residuals beyond this many RMS are left out, > 1
  double max_shift_px = 1.5;  // largest disparity change at the face's corners, px, > 0
  int edge_px = 1;            // face pixels this close to another class are left out, 0..5
  int min_pixels = 100;       // fewest face pixels to refine a plane
  int max_pixels = 4096;      // a larger face is sampled evenly down to this (time bound)
};
Status validate(const PhotometricPlaneParams& p);

struct DisparityPlane {
  double a = 0, b = 0, c = 0;  // d = a (u - u0) + b (v - v0) + c, px
  double u0 = 0, v0 = 0;       // rectified left pixel the plane is centred on
  double at(double u, double v) const { return a * (u - u0) + b * (v - v0) + c; }
};

struct PhotometricPlaneFit {
  DisparityPlane plane;
  bool accepted = false;  // false: `plane` is the initial one
  int iterations = 0;
  long pixels = 0;  // face pixels used in the last iteration
  // RMS gray residual, truncated at trim_sigma x the initial plane's RMS
  // (so both count every pixel alike): initial plane (its own gain/offset), final.
  double rms_before = 0;
  double rms_after = 0;
};

Result<PhotometricPlaneFit> refine_plane_photometric(ConstGray8View left, ConstGray8View right,
                                                     Rect right_valid,
                                                     std::span<const PixelPos> pixels,
                                                     const DisparityPlane& initial,
                                                     const PhotometricPlaneParams& params);

// The pixels of class `cls` in a class image over `roi` (rectified left
// pixels; 0xFF = unknown, e.g. no disparity): every pixel whose box of
// radius edge_px holds no other known class and either at least half of it
// `cls`, or (an unknown pixel) lies between two `cls` pixels of its row (a
// facet projects to a convex polygon; the photometric fit needs no
// disparity there). Scratch: face_pixels_scratch(W, H) ints.
// Writes at most out.size(); returns the count (0 when scratch is short).
inline std::size_t face_pixels_scratch(int width, int height) {
  (void)width;
  return 2 * static_cast<std::size_t>(height);
}
std::size_t face_pixels(ImageView<const std::uint8_t> classes, Rect roi, std::uint8_t cls,
                        int edge_px, std::span<std::int32_t> scratch, std::span<PixelPos> out);

}  // namespace petra
