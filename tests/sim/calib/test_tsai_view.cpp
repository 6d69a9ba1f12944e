// Tsai's two-step on one view of a plane: exact data give the camera back,
// including the configurations the classic formulation divides by zero on.
#include "sim/calib/tsai_view.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <string>

#include "tests/sim/calib/calib_test_scenes.hpp"

namespace petra::calib {
namespace {

PlanarView view_of(const TsaiCamera& cam, const BoardSpec& b) {
  PlanarView v;
  for (int j = 0; j < b.rows; ++j)
    for (int i = 0; i < b.cols; ++i) {
      const Eigen::Vector3d p = board_corner(b, i, j);
      auto uv = project(cam, p);
      EXPECT_TRUE(uv.ok());
      v.board_mm.emplace_back(p.x(), p.y());
      v.uv_px.push_back(*uv);
    }
  return v;
}

double rotation_error_deg(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  return Eigen::AngleAxisd(a * b.transpose()).angle() * 180.0 / 3.14159265358979323846;
}

TEST(TsaiView, ExactDataGiveTheCameraBack) {
  const BoardSpec board;
  const double poses[][3] = {{30, 0, 0}, {0, -35, 90}, {-25, 20, 180}, {15, 30, -60}};
  for (const auto& p : poses) {
    TsaiCamera truth = test::sample_camera();
    test::place_board(truth, board, p[0], p[1], p[2], 450);
    auto r = tsai_calibrate_view(view_of(truth, board), truth);  // sensor geometry given
    ASSERT_TRUE(r.ok()) << r.error().message;
    EXPECT_NEAR(r->camera.f_mm, truth.f_mm, 1e-6 * truth.f_mm);
    EXPECT_NEAR(r->camera.kappa1, truth.kappa1, 1e-6 * truth.kappa1);
    EXPECT_LT(rotation_error_deg(r->camera.R, truth.R), 1e-6);
    EXPECT_LT((r->camera.T_mm - truth.T_mm).norm(), 1e-5);
    EXPECT_LT(r->rms_px, 1e-6);
  }
}

TEST(TsaiView, TargetOriginOnTheOpticalAxis) {
  // Tsai's original step 1 divides by ty: with the target origin straight
  // ahead (tx = ty = 0) it fails. The homogeneous form does not.
  const BoardSpec board;
  TsaiCamera truth = test::sample_camera();
  test::place_board(truth, board, 25, -20, 10, 450);
  truth.T_mm.x() = 0;
  truth.T_mm.y() = 0;
  auto r = tsai_calibrate_view(view_of(truth, board), truth);
  ASSERT_TRUE(r.ok()) << r.error().message;
  EXPECT_NEAR(r->camera.f_mm, truth.f_mm, 1e-6 * truth.f_mm);
  EXPECT_LT((r->camera.T_mm - truth.T_mm).norm(), 1e-5);
}

TEST(TsaiView, FrontoParallelViewGivesNoFocalLengthUnlessItIsKnown) {
  const BoardSpec board;
  TsaiCamera truth = test::sample_camera();
  test::place_board(truth, board, 1, 0.5, 20, 450);
  const PlanarView v = view_of(truth, board);
  auto r = tsai_calibrate_view(v, truth);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.code(), Errc::degenerate);
  EXPECT_NE(std::string(r.error().message).find("parallel"), std::string::npos)
      << r.error().message;
  r = tsai_calibrate_view(v, truth, truth.f_mm);
  ASSERT_TRUE(r.ok()) << r.error().message;
  EXPECT_LT((r->camera.T_mm - truth.T_mm).norm(), 1e-5);
  EXPECT_NEAR(r->camera.kappa1, truth.kappa1, 1e-6 * truth.kappa1);
}

TEST(TsaiView, TooFewOrCollinearPointsAreRefused) {
  const BoardSpec board;
  TsaiCamera truth = test::sample_camera();
  test::place_board(truth, board, 20, 10, 0, 450);
  PlanarView v = view_of(truth, board);
  PlanarView few = v;
  few.board_mm.resize(5);
  few.uv_px.resize(5);
  EXPECT_EQ(tsai_calibrate_view(few, truth).code(), Errc::degenerate);
  PlanarView line = v;  // the first row only: all on one line
  line.board_mm.resize(9);
  line.uv_px.resize(9);
  EXPECT_EQ(tsai_calibrate_view(line, truth).code(), Errc::degenerate);
  PlanarView mismatched = v;
  mismatched.uv_px.pop_back();
  EXPECT_EQ(tsai_calibrate_view(mismatched, truth).code(), Errc::invalid_argument);
}

}  // namespace
}  // namespace petra::calib
