// Edge matching on one scanline (docs/method.md 2b step 2, paper 2.2.2): the Canny
// edge points of the left and right rows, each sorted by u, are paired by
// gray-level correlation (zero-mean normalised cross-correlation, ZNCC, over
// a 5x5 window, integer sums) under the ordering constraint, by dynamic
// programming: the matched pairs are the increasing subsequence pairing that
// maximises the sum of (ZNCC - floor). A pair must lie in the disparity
// range, have gradients of the same horizontal sign, reach the correlation
// floor, and neither point may be a horizontal edge (no position along the
// row). Part of algo/stereo/match_dp; exposed for tests.
// Memory: edge_row_scratch_bytes(left_n, right_n), at most
// (left_n + 1)(right_n + 1) + 58 (left_n + right_n) + 12 (right_n + 1) + 448 bytes
// (a 56-byte window and a 2-byte position per edge point; 64 bytes of
// alignment slack per buffer).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "algo/core/arena.hpp"
#include "algo/core/image_view.hpp"
#include "algo/core/result.hpp"

namespace petra::match {

inline constexpr int kZnccOne = 1024;  // ZNCC in Q10
inline constexpr int kZnccRadius = 2;

struct EdgePair {
  std::int16_t x_left = 0;   // image column in the left view
  std::int16_t x_right = 0;  // image column in the right view
  std::int16_t zncc_q10 = 0;
};

struct EdgeRowInputs {
  ConstGray8View left;
  ConstGray8View right;
  int y = 0;                                 // image row (both views, rectified)
  const std::uint8_t* left_edges = nullptr;  // Canny codes of columns left_x0 ..
  int left_x0 = 0;
  int left_n = 0;
  const std::uint8_t* right_edges = nullptr;
  int right_x0 = 0;
  int right_n = 0;
  int disp_min = 0;
  int disp_max = 0;
  int zncc_floor_q10 = 0;
};

std::size_t edge_row_scratch_bytes(int left_n, int right_n);

// Writes the pairs, ordered by x, into `pairs` (capacity >= left_n); returns
// how many. Scratch comes from `arena` and is released on return.
Result<int> match_edge_row(const EdgeRowInputs& in, Arena& arena, std::span<EdgePair> pairs);

// ZNCC (Q10) of the 5x5 windows at (xl, y) and (xr, y); 0 for a flat window.
int zncc_q10(ConstGray8View left, int xl, ConstGray8View right, int xr, int y);

}  // namespace petra::match
