#include "algo/camera/rectify_geometry.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>

#include "tests/support/test_rig.hpp"

namespace petra {
namespace {

StereoRig seeded_rig(std::uint64_t seed) {
  return test::bumblebee_rig(seed);
}

TEST(RectifyGeometry, CorrespondencesShareARowAndGiveTheirDepth) {
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    const StereoRig rig = seeded_rig(seed);
    auto pair = rectify_geometry(rig, 1024, 768);
    ASSERT_TRUE(pair.ok()) << pair.error().message;
    std::mt19937_64 rng(seed + 100);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (int i = 0; i < 100; ++i) {
      // A point seen by the left camera, 500..900 mm away.
      const Eigen::Vector3d pc(200 * u(rng), 150 * u(rng), 700 + 200 * u(rng));
      const Eigen::Vector3d pw = camera_to_world(rig.left, pc);
      auto ul = project(rig.left, pw);
      auto ur = project(rig.right, pw);
      ASSERT_TRUE(ul.ok() && ur.ok());
      auto rl = original_to_rectified(rig.left, pair->left, *ul);
      auto rr = original_to_rectified(rig.right, pair->right, *ur);
      ASSERT_TRUE(rl.ok() && rr.ok());
      EXPECT_NEAR(rl->y(), rr->y(), 1e-8);  // same row
      const double d = rl->x() - rr->x();
      EXPECT_GT(d, 0.0);
      auto back = rectified_point(*pair, rl->x(), rl->y(), d);
      ASSERT_TRUE(back.ok());
      EXPECT_LT((*back - pw).norm(), 1e-7 * pc.norm());
      auto proj = rectified_project(*pair, pw);
      ASSERT_TRUE(proj.ok());
      EXPECT_NEAR(proj->disparity, d, 1e-8);
      EXPECT_LT((proj->uv_left - *rl).norm(), 1e-8);
    }
  }
}

TEST(RectifyGeometry, OriginalAndRectifiedPixelsRoundTrip) {
  const StereoRig rig = seeded_rig(3);
  auto pair = rectify_geometry(rig, 1024, 768);
  ASSERT_TRUE(pair.ok());
  for (double v = 0; v < 768; v += 97)
    for (double u = 0; u < 1024; u += 101) {
      auto o = rectified_to_original(rig.right, pair->right, {u, v});
      ASSERT_TRUE(o.ok());
      auto r = original_to_rectified(rig.right, pair->right, *o);
      ASSERT_TRUE(r.ok());
      EXPECT_LT((*r - Eigen::Vector2d(u, v)).norm(), 1e-9);
    }
}

TEST(RectifyGeometry, ImageCentreStaysNearTheMiddle) {
  const StereoRig rig = seeded_rig(5);
  auto pair = rectify_geometry(rig, 1024, 768);
  ASSERT_TRUE(pair.ok());
  auto c = original_to_rectified(rig.left, pair->left, {511.5, 383.5});
  ASSERT_TRUE(c.ok());
  EXPECT_NEAR(c->x(), 511.5, 20.0);
  EXPECT_NEAR(c->y(), 383.5, 20.0);
  EXPECT_NEAR(pair->baseline_mm, 150.0, 2.0);
}

TEST(RectifyGeometry, DegenerateRigsAreRefused) {
  StereoRig rig = seeded_rig(1);
  rig.right.T_mm = rig.left.T_mm;
  rig.right.R = rig.left.R;
  EXPECT_EQ(rectify_geometry(rig, 1024, 768).code(), Errc::degenerate);
  StereoRig fwd = seeded_rig(1);
  fwd.right.R = fwd.left.R;
  fwd.right.T_mm = fwd.left.T_mm - fwd.left.R * (fwd.left.R.row(2).transpose() * 100.0);
  EXPECT_EQ(rectify_geometry(fwd, 1024, 768).code(), Errc::degenerate);
  EXPECT_EQ(rectify_geometry(seeded_rig(1), 0, 768).code(), Errc::non_positive);
  auto pair = rectify_geometry(seeded_rig(1), 1024, 768);
  ASSERT_TRUE(pair.ok());
  EXPECT_EQ(rectified_point(*pair, 10, 10, 0.0).code(), Errc::out_of_range);
}

}  // namespace
}  // namespace petra
