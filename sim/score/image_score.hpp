// Scores a disparity map and a shadow mask against the simulator's truth,
// inside a region (the ROI) of the images.
//   Disparity: pixels whose truth is finite count. bad-N (strict) = percent
//   of them whose output is invalid (non-finite) or off by more than N px;
//   coverage = percent with a valid output; bad-1 of valid = bad-1 among
//   those; mean |error| over valid outputs.
//   Shadow: a pixel is shadow when its value is >= 128. Precision
//   TP/(TP+FP), recall TP/(TP+FN), IoU TP/(TP+FP+FN); NaN when undefined.
#pragma once

#include "algo/core/image_view.hpp"
#include "algo/core/result.hpp"
#include "sim/io/image_io.hpp"

namespace petra::sim {

struct DisparityScore {
  Rect region;
  long truth_pixels = 0;
  long valid_pixels = 0;  // of those, with a finite output
  double bad1_pct = 0;
  double bad2_pct = 0;
  double coverage_pct = 0;
  double bad1_valid_pct = 0;
  double mean_abs_error_px = 0;
};

struct MaskScore {
  Rect region;
  long true_positive = 0, false_positive = 0, false_negative = 0, true_negative = 0;
  double precision = 0, recall = 0, iou = 0;
};

// Fails when sizes differ or the region is not inside the images.
Result<DisparityScore> score_disparity(const io::FloatImage& output, const io::FloatImage& truth,
                                       const Rect& region);
Result<MaskScore> score_mask(const io::GrayImage& output, const io::GrayImage& truth,
                             const Rect& region);

}  // namespace petra::sim
