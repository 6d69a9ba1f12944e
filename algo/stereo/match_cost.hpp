// Matching cost of the dense step of algo/stereo/match_dp, one image row at a time.
//   raw(x, d) = popcount(census_L(x) ^ census_R(x - d)) + min(|I_L(x) - I_R(x - d)|, 32) / 4
// with a 16-point census over the 5x5 window (the 3x3 ring and every other
// pixel of the 5x5 ring), so raw is 0..24 and fits a byte. Census compares
// each neighbour with the centre, which survives the gain and offset changes
// between two cameras; the small absolute-difference term breaks census ties
// in flat regions. The aggregated cost is the raw cost summed over a 5x9
// (x by y) box, then the minimum over 5 horizontal box positions ("shiftable
// window"), which keeps foreground objects from spreading into the background.
// A second, slanted box (its rows sheared along the disparity by half a pixel
// per row, kSlantLaneOffset) fits a surface whose disparity grows down the
// image, as a face turned up towards the sky does: the upright box spans
// 4 px of disparity there, and the face's costs blur into runs and jumps.
// Where the upright box matches a pixel poorly at every disparity (its rows
// disagree, as on such a face), each disparity keeps the cheaper of the two,
// the slanted one charged a penalty so that a level surface keeps the upright.
// All integer; the caller owns every buffer.
#pragma once

#include <cstdint>

#include "algo/core/image_view.hpp"

namespace petra::match {

inline constexpr int kCensusRadius = 2;
inline constexpr int kRawMax = 24;      // census 16 + intensity 8
inline constexpr int kRawNeutral = 12;  // a pixel that carries no information (shadow, outside)
// Padding lanes beyond the disparity range: their aggregated cost (4500)
// exceeds every real one, so they never win.
inline constexpr int kRawPad = 100;
inline constexpr int kBoxRadiusX = 2;
inline constexpr int kBoxRadiusY = 4;
inline constexpr int kShiftRadiusX = 2;
inline constexpr int kWindowRows = 2 * kBoxRadiusY + 1;
// The slanted box: window row j (top to bottom) matched at the centre's
// disparity + round(0.5 (j - 4)) px (half away from zero).
inline constexpr int kSlantLaneOffset[kWindowRows] = {-2, -2, -1, -1, 0, 1, 1, 2, 2};
inline constexpr int kMaxSlantPenalty = 1000;
// Columns of raw cost needed on each side of a row segment.
inline constexpr int kMarginX = kBoxRadiusX + kShiftRadiusX;
inline constexpr int kAggregatedMax = kRawMax * (2 * kBoxRadiusX + 1) * kWindowRows;  // 1080

// The row kernels below are compiled for fixed lane counts (the disparity
// count rounded up to 16), so each lane loop is a fixed number of vector
// operations without loop tails; kLanes = 0 is the generic version for any
// stride. X(n) is expanded for every compiled count.
inline constexpr int kMaxLanes = 4096;  // |d| <= 2047 on both sides
#define PETRA_MATCH_LANE_COUNTS(X) X(16) X(32) X(48) X(64) X(80) X(96) X(112) X(128) X(0)

// 16-bit census of row `y`, columns [x0, x0 + n), borders replicated, as
// two byte planes (bits 0-7: the 3x3 ring, bits 8-15: the outer points) so
// the cost runs in byte lanes. `rows` is scratch of 5 * (n + 4) bytes.
void census_row(ConstGray8View image, int y, int x0, int n, std::uint8_t* census_inner,
                std::uint8_t* census_outer, std::uint8_t* rows);

// Gray values of row `y`, columns [x0, x0 + n), borders replicated.
void gray_row(ConstGray8View image, int y, int x0, int n, std::uint8_t* gray);

// One row of raw cost, laid out [i][k] with `stride` (>= k_count) bytes per
// column i, written over the window row it replaces while the column sums
// (same layout, uint16) are updated: colsum += new - old. Right-view samples
// are given in REVERSED column order so that for a fixed left column i the
// disparities k = 0..k_count-1 read consecutive entries m = (n_left - 1 - i)
// + k. `override_rev[m]` != 0 replaces the cost (a right sample outside the
// image or in shadow); `neutral_left[i]` != 0 makes left column i carry no
// information (outside the image or in shadow). Lanes >= k_count get kRawPad;
// the right arrays must hold n_left + stride - 1 entries.
struct RawRowInputs {
  const std::uint8_t* census_inner_left;
  const std::uint8_t* census_outer_left;
  const std::uint8_t* gray_left;
  int n_left;
  const std::uint8_t* census_inner_right_rev;
  const std::uint8_t* census_outer_right_rev;
  const std::uint8_t* gray_right_rev;
  const std::uint8_t* override_rev;
  const std::uint8_t* neutral_left;
};
template <int kLanes>
void raw_cost_row(const RawRowInputs& in, int k_count, std::uint8_t* raw, std::uint16_t* colsum,
                  int stride);

// agg[i][k] = min over j in [i, i + 4] of the sum of colsum[j..j+4][k].
// colsum has n + 2*kMarginX columns; agg gets n; hs is scratch of 5 columns.
template <int kLanes>
void box_and_shift_row(const std::uint16_t* colsum, int n, int stride, std::uint16_t* hs,
                       std::uint16_t* agg);

// The slanted box's column sums from the window's raw cost rows (rows[j]:
// window row j, top to bottom, laid out as raw_cost_row's), wc columns.
template <int kLanes>
void slanted_column_sums(const std::uint8_t* const* rows, int wc, int stride,
                         std::uint16_t* colsum);

// poor[i] = 1 where column i's cheapest agg exceeds only_above (the box
// matches that pixel poorly at every disparity), else 0; returns how many.
template <int kLanes>
int poorly_matched(const std::uint16_t* agg, int n, int stride, int only_above, std::uint8_t* poor);

// agg = min(agg, other + penalty) in the columns i < n where where[i] != 0.
template <int kLanes>
void keep_cheaper(std::uint16_t* agg, const std::uint16_t* other, int n, int stride, int penalty,
                  const std::uint8_t* where);

}  // namespace petra::match
