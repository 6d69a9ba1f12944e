// Chessboard inner-corner detection with sub-pixel positions (ground tool).
// Steps: X-corner candidates (xcorner_candidates), grid topology
// (chessboard_grid), corners the candidates missed predicted from a local
// homography of their grid neighbours and verified in the image, then the
// board's size checked and its corners ordered.
//
// Order (the same physical corner gets the same index in every view, left or
// right, so stereo pairs correspond): index = i + j*cols, i along the board's
// `cols` axis, j along `rows`. The image of the +i axis turned towards +j is
// clockwise in the image (u right, v down), so the board frame x = i, y = j,
// z = x cross y points away from the camera. When cols + rows is odd the board
// has no 180-degree symmetry and the square between corners 0, 1, cols and
// cols+1 is the dark one; otherwise (symmetric board) corner 0 is the one
// nearest the image's top-left and `orientation_unique` is false.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "algo/core/image_view.hpp"
#include "algo/core/result.hpp"

namespace petra::calib {

struct ChessboardOptions {
  int cols = 9;                // inner corners along the board's first axis
  int rows = 6;                // and along the second
  int ring_radius_px = 0;      // X-corner ring; 0 = from the image size (then a retry at others)
  int subpix_half_window = 0;  // final refinement; 0 = from the square size, at most 5
  double min_contrast = 12;    // gray levels between dark and bright squares
};

struct ChessboardCorners {
  int cols = 0;
  int rows = 0;
  std::vector<Eigen::Vector2d> uv;  // px, index i + j*cols
  bool orientation_unique = true;   // false for a 180-degree symmetric board
  double square_px = 0;             // median distance between neighbouring corners
  int subpix_half_window = 0;       // used for the final positions
};

// Fails with a message that says what was seen, e.g.
// "board not found: 7x6 inner corners visible, expected 9x6".
Result<ChessboardCorners> detect_chessboard(ConstGray8View image, const ChessboardOptions& options);

}  // namespace petra::calib
