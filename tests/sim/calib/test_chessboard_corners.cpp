// Chessboard detection on boards rendered through a known Tsai camera: every
// corner found, in the documented order, where the camera model puts it.
#include "sim/calib/chessboard_corners.hpp"

#include <gtest/gtest.h>

#include <string>

#include "sim/calib/board_renderer.hpp"
#include "tests/sim/calib/calib_test_scenes.hpp"

namespace petra::calib {
namespace {

struct Pose {
  double ax, ay, az, distance;
};

RenderOptions camera_like() {
  RenderOptions o;
  o.blur_sigma_px = 1.0;  // a slightly soft lens
  o.noise_sigma = 2.0;    // sensor noise, gray levels
  return o;
}

TEST(ChessboardCorners, FindsEveryCornerInOrderWhereTheModelProjectsIt) {
  const BoardSpec board;
  // Tilts up to 40 degrees and the board turned all the way round: the order
  // must follow the board, not the image.
  const Pose poses[] = {{0, 0, 0, 450},      {30, 0, 0, 450},    {0, -35, 90, 500},
                        {-25, 20, 180, 420}, {10, 40, 270, 480}, {20, -20, 135, 460},
                        {-40, 0, -30, 520}};
  for (const Pose& p : poses) {
    TsaiCamera cam = test::sample_camera();
    test::place_board(cam, board, p.ax, p.ay, p.az, p.distance);
    const io::GrayImage img = render_plane(cam, chessboard_albedo(board), camera_like());
    auto found = detect_chessboard(img.view(), {});
    ASSERT_TRUE(found.ok()) << "pose " << p.ax << "," << p.ay << "," << p.az << ": "
                            << found.error().message;
    ASSERT_EQ(found->uv.size(), 54u);
    EXPECT_TRUE(found->orientation_unique);
    double worst = 0, sum = 0;
    for (int j = 0; j < 6; ++j)
      for (int i = 0; i < 9; ++i) {
        auto truth = project(cam, board_corner(board, i, j));
        ASSERT_TRUE(truth.ok());
        const double e = (found->uv[static_cast<std::size_t>(j * 9 + i)] - *truth).norm();
        worst = std::max(worst, e);
        sum += e;
      }
    // Error budget: the renderer resolves an axis-aligned edge to 1/16 px
    // (4x4 sub-samples), the gradient estimator has a sub-pixel phase bias of
    // a few hundredths on 1-px blur, and noise of 2 gray levels on a contrast
    // of 190 adds about 0.01 px. Measured: mean 0.02-0.04 px, max < 0.1 px.
    // Any ordering mistake would cost a whole square (about 30 px).
    EXPECT_LT(sum / 54, 0.05) << "pose " << p.ax << "," << p.ay << "," << p.az;
    EXPECT_LT(worst, 0.15) << "pose " << p.ax << "," << p.ay << "," << p.az;
  }
}

TEST(ChessboardCorners, ABoardOfAnotherSizeIsNamed) {
  const BoardSpec board;
  TsaiCamera cam = test::sample_camera();
  test::place_board(cam, board, 20, 10, 5, 450);
  const io::GrayImage img = render_plane(cam, chessboard_albedo(board), camera_like());
  ChessboardOptions smaller;
  smaller.cols = 7;
  auto r = detect_chessboard(img.view(), smaller);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(std::string(r.error().message).find("9x6 inner corners visible"), std::string::npos)
      << r.error().message;
  ChessboardOptions larger;
  larger.cols = 10;
  r = detect_chessboard(img.view(), larger);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(std::string(r.error().message).find("expected 10x6"), std::string::npos)
      << r.error().message;
  EXPECT_NE(std::string(r.error().message).find("9x6 grid"), std::string::npos)
      << r.error().message;
}

TEST(ChessboardCorners, NoBoardOrACutOffBoardIsRejected) {
  io::GrayImage flat(640, 480, 128);
  auto r = detect_chessboard(flat.view(), {});
  ASSERT_FALSE(r.ok());
  EXPECT_NE(std::string(r.error().message).find("no chessboard"), std::string::npos)
      << r.error().message;

  const BoardSpec board;
  TsaiCamera cam = test::sample_camera();
  test::place_board(cam, board, 10, 0, 0, 450, 170, 0);  // right third outside the image
  const io::GrayImage img = render_plane(cam, chessboard_albedo(board), camera_like());
  r = detect_chessboard(img.view(), {});
  ASSERT_FALSE(r.ok());
  EXPECT_NE(std::string(r.error().message).find("board not found"), std::string::npos)
      << r.error().message;
}

TEST(ChessboardCorners, BadBoardSizeIsRefused) {
  io::GrayImage flat(64, 64, 128);
  ChessboardOptions o;
  o.cols = 1;
  EXPECT_EQ(detect_chessboard(flat.view(), o).code(), Errc::invalid_argument);
}

}  // namespace
}  // namespace petra::calib
