// OpenCV's chessboard detector as the peer for our calibration tests: the
// real stereo set of shared/data and its 9x6 board (tests and benchmarks only).
#pragma once

#include <opencv2/calib3d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

namespace petra::test {

inline std::string chessboard_data_dir() {
  return std::string(PETRA_SOURCE_DIR) + "/../shared/data/chessboard-opencv/";
}

// findChessboardCorners + cornerSubPix with the given half window; empty when
// OpenCV finds no board.
inline std::vector<cv::Point2f> opencv_corners(const std::string& path, int half_window) {
  const cv::Mat img = cv::imread(path, cv::IMREAD_GRAYSCALE);
  std::vector<cv::Point2f> c;
  if (!cv::findChessboardCorners(img, cv::Size(9, 6), c,
                                 cv::CALIB_CB_ADAPTIVE_THRESH | cv::CALIB_CB_NORMALIZE_IMAGE))
    return {};
  cv::cornerSubPix(img, c, cv::Size(half_window, half_window), cv::Size(-1, -1),
                   cv::TermCriteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 30, 0.01));
  return c;
}

}  // namespace petra::test
