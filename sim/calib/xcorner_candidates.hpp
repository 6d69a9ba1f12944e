// X-corner candidates: points where four alternating dark and bright sectors
// meet, as at the inner corners of a chessboard.
//   1. ChESS response (Bennett & Lasenby 2014) on a ring of 16 samples of
//      radius r around each pixel of the smoothed image: large where opposite
//      sectors agree and neighbouring sectors differ; edges and blobs score
//      low. Local maxima above a threshold relative to the strongest peaks.
//   2. Sub-pixel refinement of each peak (corner_subpix).
//   3. Ring test at the refined point: 64 samples on the circle must cross
//      their mid level exactly 4 times, opposite crossings about pi apart
//      (two straight edges through the point), with enough contrast. The
//      crossings give the directions of the two edge lines through the corner.
// Memory: a float response image and the candidate list (ground code).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "algo/core/image_view.hpp"
#include "algo/core/result.hpp"

namespace petra::calib {

struct XCorner {
  Eigen::Vector2d uv;    // px
  double line_angle[2];  // the two edge lines through the corner, rad in [0, pi)
  double contrast = 0;   // mean bright minus mean dark ring sample, gray levels
  double response = 0;   // ChESS response at the integer peak
};

struct XCornerOptions {
  int ring_radius_px = 5;     // ring of the response and test; squares >= ~2.5 r px
  int expected_corners = 54;  // scales the adaptive response threshold
  double min_contrast = 12;   // gray levels between sector means
  int subpix_half_window = 4;
  int max_candidates = 3000;  // strongest peaks examined
};

// Shape of the intensity on a circle around a point.
struct RingShape {
  bool is_xcorner = false;
  int crossings = 0;
  double line_angle[2] = {0, 0};
  double contrast = 0;
};

// smooth: the smoothed image (responses, ring tests); raw: unsmoothed (sub-pixel).
std::vector<XCorner> find_xcorners(ImageView<const float> smooth, ImageView<const float> raw,
                                   const XCornerOptions& options);

RingShape analyse_ring(ImageView<const float> smooth, const Eigen::Vector2d& uv, double radius_px,
                       double min_contrast);

}  // namespace petra::calib
