// JPEG decoding against OpenCV's imread: the calibration compares corner
// positions with OpenCV, so both must see the same gray pixels.
#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include "sim/io/image_io.hpp"

namespace petra::io {
namespace {

TEST(JpegVsOpenCv, GrayPixelsIdenticalOnTheCalibrationSet) {
  const std::string dir = std::string(PETRA_SOURCE_DIR) + "/../shared/data/chessboard-opencv/";
  for (const char* name : {"left01.jpg", "right07.jpg", "left14.jpg"}) {
    auto ours = read_gray_image(dir + name);
    ASSERT_TRUE(ours.ok()) << ours.error().message;
    const cv::Mat cv_img = cv::imread(dir + name, cv::IMREAD_GRAYSCALE);
    ASSERT_FALSE(cv_img.empty()) << name;
    ASSERT_EQ(ours->width, cv_img.cols);
    ASSERT_EQ(ours->height, cv_img.rows);
    long differing = 0;
    for (int y = 0; y < cv_img.rows; ++y)
      for (int x = 0; x < cv_img.cols; ++x)
        differing += ours->view()(x, y) != cv_img.at<std::uint8_t>(y, x);
    EXPECT_EQ(differing, 0) << name;
  }
}

}  // namespace
}  // namespace petra::io
