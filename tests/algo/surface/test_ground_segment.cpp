#include "algo/surface/ground_segment.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "tests/support/angles.hpp"
#include "tests/support/heap_counter.hpp"
#include "tests/support/synthetic_scene.hpp"

namespace petra {
namespace {

const test::PinholeView kGroundView = test::look_at({30, -600, 500}, {0, 0, 20});

Rect rock_roi(int pad = 40) {
  // Bounding box of the rock's corners in the image, padded with ground.
  double u0 = 1e9, v0 = 1e9, u1 = -1e9, v1 = -1e9;
  for (double x : {-40.0, 40.0})
    for (double y : {-30.0, 30.0})
      for (double z : {0.0, 55.0}) {
        const Eigen::Vector2d p = kGroundView.project({x, y, z});
        u0 = std::min(u0, p.x());
        v0 = std::min(v0, p.y());
        u1 = std::max(u1, p.x());
        v1 = std::max(v1, p.y());
      }
  return Rect{static_cast<int>(u0) - pad, static_cast<int>(v0) - pad,
              static_cast<int>(u1 - u0) + 2 * pad, static_cast<int>(v1 - v0) + 2 * pad};
}

struct Outcome {
  Result<GroundResultT<double>> result;
  std::vector<PointClass> labels;
};

Outcome segment(const test::Cloud& cloud, const Rect& roi, ClickPx click = {},
                const GroundParams& params = {}) {
  std::vector<PointClass> labels(cloud.xyz.size());
  auto r =
      segment_ground<double>(cloud.xyz, cloud.px, roi, click, kGroundView.centre(), params, labels);
  return {r, labels};
}

std::string message(const Outcome& o) {
  return o.result.ok() ? "" : o.result.error().message;
}

TEST(GroundSegment, FindsTheGroundPlaneAndTheRock) {
  const Rect roi = rock_roi();
  const test::Cloud cloud = test::render(kGroundView, roi, test::ridge_rock());
  Outcome o = segment(cloud, roi);
  ASSERT_TRUE(o.result.ok()) << message(o);
  const auto& g = *o.result;
  EXPECT_TRUE(g.converged);
  // Exact data; the residue is the rock's foot inside the 0.5 mm trim band.
  EXPECT_LT(test::angle_deg(g.plane.normal, Eigen::Vector3d::UnitZ()), 1e-3);
  EXPECT_NEAR(g.plane.d, 0.0, 0.01);
  EXPECT_LT(g.rms_mm, 0.05);
  // Every ground point is ground; every rock point above the split is rock.
  const double split = g.rock_centre_mm / 2;
  std::size_t wrong = 0;
  for (std::size_t i = 0; i < cloud.xyz.size(); ++i) {
    const bool ground = cloud.surface[i] < 0;
    if (ground) wrong += o.labels[i] != PointClass::ground;
    if (!ground && cloud.xyz[i].z() > split + 0.5) wrong += o.labels[i] != PointClass::rock;
  }
  EXPECT_EQ(wrong, 0u);
  EXPECT_GT(g.rock_points, 1000u);
}

TEST(GroundSegment, NoisyCloudStillGivesAnAccuratePlane) {
  const Rect roi = rock_roi();
  const test::Cloud cloud = test::render(kGroundView, roi, test::ridge_rock(), 0.5, 7);
  Outcome o = segment(cloud, roi);
  ASSERT_TRUE(o.result.ok()) << message(o);
  EXPECT_LT(test::angle_deg(o.result->plane.normal, Eigen::Vector3d::UnitZ()), 0.1);
  EXPECT_NEAR(o.result->plane.d, 0.0, 0.2);
  EXPECT_NEAR(o.result->rms_mm, 0.5 * 0.75, 0.25);  // noise along rays, mostly off-plane
}

TEST(GroundSegment, ClickSeedsTheRockAndIsChecked) {
  const Rect roi = rock_roi();
  test::Cloud cloud = test::render(kGroundView, roi, test::ridge_rock());
  const Eigen::Vector2d top = kGroundView.project({10, 0, 50});
  ClickPx click{true, static_cast<int>(std::lround(top.x())),
                static_cast<int>(std::lround(top.y()))};
  Outcome o = segment(cloud, roi, click);
  ASSERT_TRUE(o.result.ok()) << message(o);
  EXPECT_EQ(o.labels[o.result->click_point], PointClass::rock);
  EXPECT_LT(test::angle_deg(o.result->plane.normal, Eigen::Vector3d::UnitZ()), 1e-3);

  ClickPx outside{true, roi.x - 5, roi.y + 10};
  o = segment(cloud, roi, outside);
  ASSERT_FALSE(o.result.ok());
  EXPECT_EQ(o.result.code(), Errc::out_of_range);
  EXPECT_NE(message(o).find("outside the ROI"), std::string::npos);

  ClickPx ground{true, roi.x + 3, roi.y + roi.h - 3};
  o = segment(cloud, roi, ground);
  ASSERT_FALSE(o.result.ok());
  EXPECT_NE(message(o).find("on the ground"), std::string::npos);

  // A hole (shadow, no match) around the click.
  test::Cloud holed;
  for (std::size_t i = 0; i < cloud.xyz.size(); ++i) {
    const int du = cloud.px[i].u - click.u, dv = cloud.px[i].v - click.v;
    if (du * du + dv * dv <= 36) continue;
    holed.xyz.push_back(cloud.xyz[i]);
    holed.px.push_back(cloud.px[i]);
    holed.surface.push_back(cloud.surface[i]);
  }
  o = segment(holed, roi, click);
  ASSERT_FALSE(o.result.ok());
  EXPECT_NE(message(o).find("no depth within"), std::string::npos);
}

TEST(GroundSegment, AllPointsOnOnePlaneMeansNoRock) {
  const Rect roi{100, 500, 120, 80};  // ground only, far from the rock
  const test::Cloud cloud = test::render(kGroundView, roi, test::ridge_rock());
  for (int s : cloud.surface) ASSERT_EQ(s, -1);
  Outcome o = segment(cloud, roi);
  ASSERT_FALSE(o.result.ok());
  EXPECT_EQ(o.result.code(), Errc::degenerate);
  EXPECT_NE(message(o).find("no rock"), std::string::npos);
}

TEST(GroundSegment, ARoiInsideTheRockHasNoGround) {
  // The ROI on the rock's roof: two facets meeting at the ridge, no ground.
  const Eigen::Vector2d c0 = kGroundView.project({-32, -22, 40}),
                        c1 = kGroundView.project({32, 22, 45});
  const Rect roi{static_cast<int>(std::min(c0.x(), c1.x())) + 2,
                 static_cast<int>(std::min(c0.y(), c1.y())) + 2,
                 static_cast<int>(std::abs(c1.x() - c0.x())) - 4,
                 static_cast<int>(std::abs(c1.y() - c0.y())) - 4};
  const test::Cloud cloud = test::render(kGroundView, roi, test::ridge_rock());
  for (int s : cloud.surface) ASSERT_GE(s, 0);  // all rock
  Outcome o = segment(cloud, roi);
  ASSERT_FALSE(o.result.ok());
  EXPECT_NE(message(o).find("no ground in the ROI"), std::string::npos) << message(o);
}

TEST(GroundSegment, CollinearCornerSeedsAreAnError) {
  Rect roi = rock_roi();
  roi.y = roi.y + roi.h - 1;  // one row: the seeds are collinear in 3-D
  roi.h = 1;
  const test::Cloud cloud = test::render(kGroundView, roi, test::ridge_rock());
  Outcome o = segment(cloud, roi);
  ASSERT_FALSE(o.result.ok());
  EXPECT_EQ(o.result.code(), Errc::degenerate);
  EXPECT_NE(message(o).find("collinear"), std::string::npos);
}

TEST(GroundSegment, TooFewPointsAndBadParameters) {
  const Rect roi = rock_roi();
  test::Cloud cloud = test::render(kGroundView, roi, test::ridge_rock());
  test::Cloud few;
  for (std::size_t i = 0; i < 20; ++i) {
    few.xyz.push_back(cloud.xyz[i]);
    few.px.push_back(cloud.px[i]);
  }
  Outcome o = segment(few, roi);
  ASSERT_FALSE(o.result.ok());
  EXPECT_NE(message(o).find("need at least 30"), std::string::npos);
  GroundParams p;
  p.epsilon = 0;
  o = segment(cloud, roi, {}, p);
  EXPECT_NE(message(o).find("epsilon"), std::string::npos);
  std::vector<PointClass> labels(3);
  auto r = segment_ground<double>(cloud.xyz, cloud.px, roi, {}, kGroundView.centre(), {}, labels);
  EXPECT_EQ(r.code(), Errc::invalid_argument);
}

TEST(GroundSegment, NoHeap) {
  const Rect roi = rock_roi();
  const test::Cloud cloud = test::render(kGroundView, roi, test::ridge_rock(), 0.3, 3);
  std::vector<PointClass> labels(cloud.xyz.size());
  test::HeapScope scope;
  auto r = segment_ground<double>(cloud.xyz, cloud.px, roi, {}, kGroundView.centre(), {}, labels);
  EXPECT_EQ(scope.allocations(), 0u);
  EXPECT_TRUE(r.ok());
}

}  // namespace
}  // namespace petra
