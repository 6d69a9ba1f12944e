// Chessboard corners on the real OpenCV stereo set against OpenCV's own
// detector: findChessboardCorners + cornerSubPix with the window ours chose
// (11x11 on this set). The 23x23 window of OpenCV's stereo_calib sample is not
// used: on left02 and right02 it reaches the board's border and pulls corners
// by up to 6 px. OpenCV orders corners per image in its own way, so corners
// are matched by position; our order is tested on rendered boards.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "tests/support/opencv_chessboard.hpp"

#include "sim/calib/chessboard_corners.hpp"
#include "sim/io/image_io.hpp"

namespace petra::calib {
namespace {

const char* const kPairs[] = {"01", "02", "03", "04", "05", "06", "07",
                              "08", "09", "11", "12", "13", "14"};

using petra::test::opencv_corners;

TEST(ChessboardVsOpenCv, CornersWithinATenthOfAPixelOfOpenCv) {
  double sum = 0, worst = 0;
  int count = 0;
  for (const char* side : {"left", "right"})
    for (const char* id : kPairs) {
      const std::string path = petra::test::chessboard_data_dir() + side + id + ".jpg";
      auto img = io::read_gray_image(path);
      ASSERT_TRUE(img.ok()) << img.error().message;
      auto ours = detect_chessboard(img->view(), {});
      ASSERT_TRUE(ours.ok()) << path << ": " << ours.error().message;
      const std::vector<cv::Point2f> ref = opencv_corners(path, ours->subpix_half_window);
      ASSERT_EQ(ref.size(), 54u) << path;
      double image_sum = 0, image_worst = 0;
      for (const cv::Point2f& r : ref) {
        double best = 1e9;
        for (const Eigen::Vector2d& p : ours->uv)
          best = std::min(best, std::hypot(p.x() - double{r.x}, p.y() - double{r.y}));
        image_sum += best;
        image_worst = std::max(image_worst, best);
      }
      std::printf("%s%s: mean %.4f px, max %.4f px (square %.1f px, window %d)\n", side, id,
                  image_sum / 54, image_worst, ours->square_px, ours->subpix_half_window);
      sum += image_sum;
      count += 54;
      worst = std::max(worst, image_worst);
    }
  const double mean = sum / count;
  std::printf("all 26 images: mean %.4f px, max %.4f px\n", mean, worst);
  EXPECT_LT(mean, 0.1);
  EXPECT_LT(worst, 0.5);  // no corner is a different corner (the spacing is ~25 px)
}

}  // namespace
}  // namespace petra::calib
