// The whole calibration on images: boards rendered through a known stereo
// rig (blur, noise, distortion) and written as PNG files, plus the files an
// operator's folder may also hold: unreadable, another size, unpaired, empty.
#include "sim/calib/board_images.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <filesystem>
#include <string>

#include "sim/calib/board_renderer.hpp"
#include "sim/calib/stereo_calibration.hpp"
#include "sim/io/image_io.hpp"
#include "tests/sim/calib/calib_test_scenes.hpp"
#include "tests/support/cached_dir.hpp"

namespace petra::calib {
namespace {

namespace fs = std::filesystem;

class RenderedSet : public ::testing::Test {
 protected:
  // Written once per build tree, shared by this suite's test processes.
  static void SetUpTestSuite() {
    dir_ = petra::test::cached_dir("calib_board_set", "8 boards, pairs 8-11 broken",
                                   petra::test::this_executable(), write_set);
    ASSERT_FALSE(dir_.empty()) << "could not write the board set";
  }

  static bool write_set(const fs::path& dir) {
    const StereoRig rig = test::sample_rig();
    const BoardSpec board;
    RenderOptions ro;
    ro.blur_sigma_px = 1.0;
    ro.noise_sigma = 2.0;
    bool ok = true;
    for (int k = 0; k < kBoards; ++k)
      for (int side = 0; side < 2; ++side) {
        ro.seed = static_cast<std::uint64_t>(10 * k + side + 1);
        const TsaiCamera cam = test::camera_seeing(rig, side, board, test::kPoses[k]);
        const io::GrayImage img = render_plane(cam, chessboard_albedo(board), ro);
        ok = ok && io::write_png(file(dir, side, k), img.view()).ok();
      }
    std::error_code ec;
    // Pair 8: the left file is not an image.
    ok = ok && io::write_text_file(file(dir, 0, 8), "not an image").ok();
    ok = ok && fs::copy_file(file(dir, 1, 0), file(dir, 1, 8), ec);
    // Pair 9: the left image has another size.
    ok = ok && io::write_png(file(dir, 0, 9), io::GrayImage(320, 240, 128).view()).ok();
    ok = ok && fs::copy_file(file(dir, 1, 1), file(dir, 1, 9), ec);
    // 10: a right image without a left one.
    ok = ok && fs::copy_file(file(dir, 1, 2), file(dir, 1, 10), ec);
    // Pair 11: no board at all.
    ok = ok && io::write_png(file(dir, 0, 11), io::GrayImage(640, 480, 128).view()).ok();
    ok = ok && io::write_png(file(dir, 1, 11), io::GrayImage(640, 480, 128).view()).ok();
    return ok;
  }

  static std::string file(const fs::path& dir, int side, int k) {
    char name[32];
    std::snprintf(name, sizeof name, "%s%02d.png", side == 0 ? "left" : "right", k);
    return (dir / name).string();
  }
  static std::string path(int side, int k) { return file(dir_, side, k); }
  static std::string pattern(const char* side) {
    return (dir_ / (std::string(side) + "*.png")).string();
  }

  static constexpr int kBoards = 8;
  static fs::path dir_;
};

fs::path RenderedSet::dir_;

bool rejected_for(const BoardImages& b, const std::string& file, const std::string& reason) {
  for (const RejectedImage& r : b.rejected)
    if (r.path == file && r.reason.find(reason) != std::string::npos) return true;
  return false;
}

TEST_F(RenderedSet, EveryUnusableImageIsNamedWithItsReason) {
  auto found = find_boards(pattern("left"), pattern("right"), {});
  ASSERT_TRUE(found.ok()) << found.error().message;
  for (const RejectedImage& r : found->rejected)
    std::printf("rejected %s: %s\n", r.path.c_str(), r.reason.c_str());
  EXPECT_TRUE(rejected_for(*found, path(0, 8), "unknown image format"));
  EXPECT_TRUE(rejected_for(*found, path(0, 9), "image is 320x240"));
  EXPECT_TRUE(rejected_for(*found, path(1, 10), "no image of the other camera"));
  EXPECT_TRUE(rejected_for(*found, path(0, 11), "no chessboard"));
  EXPECT_TRUE(rejected_for(*found, path(1, 11), "no chessboard"));
  EXPECT_EQ(found->rejected.size(), 5u);
  EXPECT_EQ(found->pairs.size(), 11u);  // 00-09 and 11; 10 has no partner
}

TEST_F(RenderedSet, RenderedBoardsGiveTheRigBack) {
  // Corners found on the rendered images are within about 0.03 px of the
  // model's projections (test_chessboard_corners), which the fit sees as
  // noise of that size; 8 pairs instead of 12. The tolerances below are
  // those of the 0.1 px corner-noise test (StereoCalibration), which this
  // set meets with a margin.
  auto found = find_boards(pattern("left"), pattern("right"), {});
  ASSERT_TRUE(found.ok()) << found.error().message;
  const StereoRig truth = test::sample_rig();
  StereoCalibOptions o;
  o.square_mm = BoardSpec{}.square_mm;
  for (TsaiCamera* s : {&o.left_sensor, &o.right_sensor}) {
    s->width = 640;
    s->height = 480;
    s->dx_mm = s->dy_mm = truth.left.dx_mm;
  }
  auto cal = calibrate_stereo(found->pairs, o);
  ASSERT_TRUE(cal.ok()) << cal.error().message;
  std::printf(
      "RMS %.4f px; left f %.5f kappa1 %.5f cx %.2f cy %.2f sx %.5f; right f %.5f kappa1 %.5f cx "
      "%.2f "
      "cy %.2f sx %.5f; baseline %.3f mm\n",
      cal->rms_px, cal->rig.left.f_mm, cal->rig.left.kappa1, cal->rig.left.cx_px,
      cal->rig.left.cy_px, cal->rig.left.sx, cal->rig.right.f_mm, cal->rig.right.kappa1,
      cal->rig.right.cx_px, cal->rig.right.cy_px, cal->rig.right.sx, cal->baseline_mm);
  EXPECT_EQ(cal->pairs.size(), 8u);  // pairs 8 and 9 have a right image only
  // ... and those right images repeat boards 0 and 1: counted once.
  bool noted = false;
  for (const std::string& n : cal->notes)
    noted |= n.find("right08.png: same board position as") != std::string::npos;
  EXPECT_TRUE(noted);
  EXPECT_LT(cal->rms_px, 0.1);
  for (int side = 0; side < 2; ++side) {
    const TsaiCamera& t = side == 0 ? truth.left : truth.right;
    const TsaiCamera& c = side == 0 ? cal->rig.left : cal->rig.right;
    EXPECT_NEAR(c.f_mm, t.f_mm, 4e-3 * t.f_mm);
    EXPECT_NEAR(c.kappa1, t.kappa1, 0.06 * t.kappa1);
    EXPECT_NEAR(c.cx_px, t.cx_px, 3.0);
    EXPECT_NEAR(c.cy_px, t.cy_px, 3.0);
    EXPECT_NEAR(c.sx, t.sx, 1e-3);
  }
  EXPECT_LT(Eigen::AngleAxisd(cal->rig.right.R * truth.right.R.transpose()).angle() / test::kDeg,
            0.3);
  EXPECT_LT((camera_centre_world(cal->rig.right) - camera_centre_world(truth.right)).norm(), 0.5);
}

TEST_F(RenderedSet, WrongBoardSizeRejectsEveryImage) {
  ChessboardOptions seven;
  seven.cols = 7;
  auto found = find_boards(pattern("left"), pattern("right"), seven);
  ASSERT_TRUE(found.ok()) << found.error().message;
  EXPECT_TRUE(
      rejected_for(*found, path(0, 3), "9x6 inner corners visible, more than the 7x6 expected"));
  StereoCalibOptions o;
  o.cols = 7;
  for (TsaiCamera* s : {&o.left_sensor, &o.right_sensor}) {
    s->width = 640;
    s->height = 480;
    s->dx_mm = s->dy_mm = 0.006;
  }
  auto cal = calibrate_stereo(found->pairs, o);
  ASSERT_FALSE(cal.ok());
  EXPECT_NE(std::string(cal.error().message).find("need at least 3"), std::string::npos)
      << cal.error().message;
}

TEST(BoardImages, PatternsWithoutFilesAreNamed) {
  auto found = find_boards("/nonexistent/left*.png", "/nonexistent/right*.png", {});
  ASSERT_FALSE(found.ok());
  EXPECT_NE(std::string(found.error().message).find("no files match '/nonexistent/left*.png'"),
            std::string::npos)
      << found.error().message;
}

}  // namespace
}  // namespace petra::calib
