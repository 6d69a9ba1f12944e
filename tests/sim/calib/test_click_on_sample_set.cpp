// Epipolar geometry and click transfer on real images: OpenCV's sample stereo
// set, calibrated by us. The detected right corners are the truth for clicks
// on the detected left corners.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>

#include "algo/camera/epipolar.hpp"
#include "sim/calib/board_images.hpp"
#include "sim/calib/stereo_calibration.hpp"
#include "sim/io/image_io.hpp"

namespace petra::calib {
namespace {

class SampleSet : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::string d = std::string(PETRA_SOURCE_DIR) + "/../shared/data/chessboard-opencv/";
    auto found = find_boards(d + "left*.jpg", d + "right*.jpg", {});
    ASSERT_TRUE(found.ok()) << found.error().message;
    boards_ = *found;
    StereoCalibOptions o;
    o.square_mm = 1;
    for (TsaiCamera* s : {&o.left_sensor, &o.right_sensor}) {
      s->width = 640;
      s->height = 480;
      s->dx_mm = s->dy_mm = 0.00465;
    }
    auto cal = calibrate_stereo(boards_.pairs, o);
    ASSERT_TRUE(cal.ok()) << cal.error().message;
    rig_ = cal->rig;
  }
  BoardImages boards_;
  StereoRig rig_;
};

TEST_F(SampleSet, RightCornersLieOnTheLeftCornersEpipolarLines) {
  auto f = fundamental_matrix(rig_);
  ASSERT_TRUE(f.ok());
  double sum = 0, worst = 0;
  int n = 0;
  for (const StereoPairCorners& p : boards_.pairs)
    for (std::size_t k = 0; k < p.left_uv.size(); ++k) {
      const Eigen::Vector3d line = epipolar_line(*f, ideal_pixel(rig_.left, p.left_uv[k]));
      const double d = std::abs(line.dot(ideal_pixel(rig_.right, p.right_uv[k]).homogeneous()));
      sum += d;
      worst = std::max(worst, d);
      ++n;
    }
  std::printf("distance of %d right corners from their epipolar lines: mean %.3f px, max %.3f px\n",
              n, sum / n, worst);
  // The stereo fit's RMS is 0.25 px per corner; a line distance is one
  // component of it for one camera, so its mean is about 0.1-0.2 px.
  EXPECT_LT(sum / n, 0.25);
  EXPECT_LT(worst, 1.0);
}

TEST_F(SampleSet, ClicksOnLeftCornersLandOnTheRightCorners) {
  // Every fifth corner of every pair. A chessboard repeats itself every two
  // squares, so along the whole ray a corner two squares away can score as
  // well as the true one: the search is limited to +-25 % of the true depth
  // (what an operator's depth window would do), and every full-ray match
  // that lands on the wrong corner must at least be flagged: ambiguous
  // (runner-up within 0.05 of the best) or at the end of the searched range,
  // the two warnings of `petra click`.
  double sum = 0, worst = 0;
  int n = 0, wrong_full_ray = 0, unflagged_wrong = 0;
  for (const StereoPairCorners& p : boards_.pairs) {
    auto l = io::read_gray_image(p.left_name);
    auto r = io::read_gray_image(p.right_name);
    ASSERT_TRUE(l.ok() && r.ok());
    for (std::size_t k = 0; k < p.left_uv.size(); k += 5) {
      auto meet =
          meet_rays(pixel_to_ray(rig_.left, p.left_uv[k]), pixel_to_ray(rig_.right, p.right_uv[k]));
      ASSERT_TRUE(meet.ok());
      const double z = world_to_camera(rig_.left, meet->point_mm).z();
      ClickOptions window;
      window.min_depth_mm = 0.8 * z;
      window.max_depth_mm = 1.25 * z;
      auto m = transfer_click(rig_, l->view(), r->view(), p.left_uv[k], window);
      ASSERT_TRUE(m.ok()) << m.error().message;
      const double e = (m->right_px - p.right_uv[k]).norm();
      sum += e;
      worst = std::max(worst, e);
      ++n;
      ClickOptions full;
      full.min_depth_mm = 1.5 * 3.3;  // 1.5 baselines: the nearest boards are 3 baselines away
      auto all = transfer_click(rig_, l->view(), r->view(), p.left_uv[k], full);
      ASSERT_TRUE(all.ok()) << all.error().message;
      if ((all->right_px - p.right_uv[k]).norm() > 1.0) {
        ++wrong_full_ray;
        if (all->runner_up <= all->score - 0.05 && !all->at_search_end) ++unflagged_wrong;
      }
    }
  }
  std::printf(
      "%d clicks: match to detected corner mean %.3f px, max %.3f px; full ray: %d on another "
      "corner, "
      "%d of them not flagged\n",
      n, sum / n, worst, wrong_full_ray, unflagged_wrong);
  EXPECT_LT(sum / n, 0.35);
  EXPECT_LT(worst, 1.0);
  EXPECT_EQ(unflagged_wrong, 0);
}

}  // namespace
}  // namespace petra::calib
