// Reads the images of a stereo calibration set and finds the board in each
// (ground tool). Every image that cannot be used is listed with the reason:
// unreadable, a size different from the first image of its camera, no
// partner, or the board not found (chessboard_corners' message).
#pragma once

#include <string>
#include <vector>

#include "algo/core/result.hpp"
#include "sim/calib/chessboard_corners.hpp"
#include "sim/calib/stereo_calibration.hpp"

namespace petra::calib {

struct RejectedImage {
  std::string path;
  std::string reason;
};

struct BoardImages {
  std::vector<StereoPairCorners> pairs;  // every pair; a side is empty where rejected
  std::vector<RejectedImage> rejected;
  int left_width = 0, left_height = 0;
  int right_width = 0, right_height = 0;
  bool orientation_unique = true;  // false: a 180-degree symmetric board (see chessboard_corners)
};

// Fails only when a pattern matches no file or no image of a camera is readable.
Result<BoardImages> find_boards(const std::string& left_pattern, const std::string& right_pattern,
                                const ChessboardOptions& board);

}  // namespace petra::calib
