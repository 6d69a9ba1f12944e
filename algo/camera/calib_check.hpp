// Calibration check of a rectified pair: the vertical disparity of matched
// features. With a good calibration a point lies on the same row in both
// rectified views; a drifted rig moves the right view's rows.
//
// Inputs: the rectified left and right images (same size), the left area to
// sample (`left_area`, e.g. the rectified ROI), the right area that holds
// valid rectified pixels (`right_area`), and the horizontal disparity range
// [disp_min, disp_max] px already found (right x = left x - d).
// Method: the ROI is cut into a grid of at most max_features cells; each
// cell gives its strongest corner (integer score min(sum gx^2, sum gy^2)
// over a 5x5 window, gradients by central differences). Each corner's
// (2r+1)^2 patch is matched in the right view by zero-mean SAD (integer)
// over every disparity of the range and every row offset within
// +-vertical_search_px. A match is kept when its cost is below
// `uniqueness` times the best cost at a disparity >= 2 px away and its row
// offset is not at the search's edge; the offset gets a parabolic
// sub-pixel fit over the row profile (each row's best of d-1..d+1).
// Outputs (px): median row offset (right row - left row; + = the right
// view's content sits lower), spread = 1.4826 x MAD (a robust 1-sigma), the
// count of kept features and a verdict: unknown below min_features kept,
// drifted when |offset| > drift_px, else ok. A drifted pair is corrected by
// its user (the pipeline moves the right view's rows by the offset before
// matching, Rectifier::rectify_rows_moved, when correct_drift is set): the
// verdict is then `corrected`, with the rows moved in corrected_px.
// Memory: calib_check_scratch_bytes(params) from the caller's arena (one
// float per feature, twice; three int rows of the disparity range: the
// per-disparity best, one row offset's patch sums and costs), released on
// return. No heap.
// Work: at most max_features x (2V+1) x (disp range) patch costs.
#pragma once

#include <cstddef>
#include <cstdint>

#include "algo/core/arena.hpp"
#include "algo/core/image_view.hpp"
#include "algo/core/result.hpp"

namespace petra {

struct CalibCheckParams {
  int max_features = 256;      // grid cells over the area, 16..4096
  int patch_radius = 3;        // 7x7 patches, 1..7
  int vertical_search_px = 5;  // row offsets searched, 1..8 (+-3 under-reads a 2-3 px drift)
  int min_corner_score = 400;  // min(sum gx^2, sum gy^2) over 5x5 (central differences)
  double uniqueness = 0.8;     // best cost < this x the best >= 2 px away in d, (0, 1]
  int min_features = 20;       // fewer kept -> verdict unknown
  double drift_px = 0.5;       // |median offset| above this -> drifted
  // A drifted pair's right view moved by the offset before matching (a
  // rotation of the rig about its baseline, which the pair itself measures).
  bool correct_drift = true;
};
Status validate(const CalibCheckParams& p);

enum class CalibVerdict : std::uint8_t { unknown = 0, ok = 1, drifted = 2, corrected = 3 };
const char* to_string(CalibVerdict v);

struct CalibCheck {
  bool present = false;           // false: the check was not run
  double vertical_offset_px = 0;  // median, right row - left row
  double spread_px = 0;           // 1.4826 x median absolute deviation
  int features = 0;               // kept matches
  int candidates = 0;             // corners tried
  CalibVerdict verdict = CalibVerdict::unknown;
  double corrected_px = 0;  // rows the right view was moved up by before matching (0: none)
};

std::size_t calib_check_scratch_bytes(const CalibCheckParams& p);

// Errors: bad parameters, images of different sizes, areas outside the
// images, empty or reversed disparity range, arena too small.
Result<CalibCheck> check_calibration(ConstGray8View left, ConstGray8View right, Rect left_area,
                                     Rect right_area, int disp_min, int disp_max,
                                     const CalibCheckParams& params, Arena& scratch);

}  // namespace petra
