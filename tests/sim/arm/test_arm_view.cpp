#include "sim/arm/arm_view.hpp"

#include <gtest/gtest.h>

#include <string>

namespace petra::sim {
namespace {

constexpr const char* kPlanes = R"({"planes":[
  {"normal":[0.3,-0.5,0.8124],"centroid_mm":[-20,520,90],"area_mm2":2500,"rms_mm":0.4,"triangles":120},
  {"normal":[-0.75,-0.3,0.5895],"centroid_mm":[250,420,60],"area_mm2":900,"rms_mm":0.6,"triangles":40}],
  "ground":{"normal":[0,0,1],"d_mm":0},
  "stats":{"dense_points":100,"filtered_points":90,"disparity_min":-21,"disparity_max":20}})";

TEST(PlanesFile, ReadsPlanesAndGround) {
  auto f = parse_planes_json(kPlanes);
  ASSERT_TRUE(f.ok()) << f.error().message;
  ASSERT_EQ(f->planes.size(), 2u);
  EXPECT_NEAR(f->planes[0].normal.norm(), 1.0, 1e-12);
  EXPECT_DOUBLE_EQ(f->planes[1].centroid_mm.x(), 250.0);
  EXPECT_DOUBLE_EQ(f->planes[0].area_mm2, 2500.0);
  ASSERT_TRUE(f->ground.has_value());
  EXPECT_DOUBLE_EQ((*f->ground)[2], 1.0);
}

TEST(PlanesFile, ErrorsNameTheField) {
  struct Case {
    const char* text;
    const char* field;
  } cases[] = {
      {R"({"planes":[{"normal":[0,0,2],"centroid_mm":[0,0,0]}]})", "planes[0].normal"},
      {R"({"planes":[{"normal":[0,0,1]}]})", "planes[0].centroid_mm"},
      {R"({"planes":[{"normal":[0,0,1],"centroid_mm":[0,"x",0]}]})", "planes[0].centroid_mm[1]"},
      {R"({"plane":[]})", "planes"},
      {R"({"planes":[],"ground":{"normal":[0,0,1]}})", "ground.d_mm"},
      {R"({"planes":[)", "json"},
  };
  for (const Case& c : cases) {
    auto f = parse_planes_json(c.text);
    ASSERT_FALSE(f.ok()) << c.text;
    EXPECT_NE(std::string(f.error().message).find(c.field), std::string::npos) << f.error().message;
  }
}

ArmViewInput input(std::size_t chosen) {
  auto f = parse_planes_json(kPlanes);
  ArmViewInput in;
  in.planes = f->planes;
  in.ground = f->ground;
  in.chosen = chosen;
  return in;
}

int count_pixels(const io::RgbImage& img, Rgb c) {
  int n = 0;
  for (int y = 0; y < img.height; ++y) {
    for (int x = 0; x < img.width; ++x) {
      const std::uint8_t* p = img.at(x, y);
      n += p[0] == c.r && p[1] == c.g && p[2] == c.b;
    }
  }
  return n;
}

TEST(ArmView, AReachablePlaneIsPlannedAndDrawn) {
  const ArmViewInput in = input(0);
  auto view = plan_arm_view(in);
  ASSERT_TRUE(view.ok());
  ASSERT_TRUE(view->plan.ok()) << view->plan.error(in.limits).message;
  // The planned contact pose puts the tip on the centroid, axis on -normal.
  const arm::ToolPose t = arm::forward_kinematics(in.geometry, view->plan.approach.contact_q);
  EXPECT_LT((t.tip_mm - in.planes[0].centroid_mm).norm(), 1e-6);
  EXPECT_GT(-t.axis.dot(in.planes[0].normal), 1.0 - 1e-9);
  ASSERT_GE(view->summary.size(), 4u);
  EXPECT_NE(view->summary[1].find("contact"), std::string::npos);
  RasterCanvas canvas(1400, 900, {255, 255, 255});
  draw_arm_view(in, *view, canvas);
  // Arm links in their blue, in three panels: thousands of fully covered pixels.
  EXPECT_GT(count_pixels(canvas.image(), {35, 80, 160}), 3000);
  EXPECT_EQ(count_pixels(canvas.image(), {200, 20, 20}), 0);  // no refusal text
  SvgCanvas svg(1400, 900, {255, 255, 255});
  draw_arm_view(in, *view, svg);
  const std::string text = svg.finish();
  EXPECT_EQ(text.rfind("<svg", 0), 0u);
  EXPECT_NE(text.find("contact:"), std::string::npos);
  EXPECT_NE(text.find("<clipPath"), std::string::npos);
}

TEST(ArmView, ARefusedPlaneShowsTheReasonInRed) {
  const ArmViewInput in = input(1);
  auto view = plan_arm_view(in);
  ASSERT_TRUE(view.ok());
  ASSERT_FALSE(view->plan.ok());
  EXPECT_EQ(view->plan.refusal.reason, arm::ArmReason::joint_limit);
  EXPECT_EQ(view->plan.refusal.joint, 5);
  EXPECT_NE(view->summary[1].find("REFUSED"), std::string::npos);
  RasterCanvas canvas(1400, 900, {255, 255, 255});
  draw_arm_view(in, *view, canvas);
  EXPECT_GT(count_pixels(canvas.image(), {200, 20, 20}), 500);
}

TEST(ArmView, BadInputIsAnError) {
  ArmViewInput in = input(0);
  in.chosen = 2;
  EXPECT_EQ(plan_arm_view(in).code(), Errc::out_of_range);
  in.planes.clear();
  EXPECT_EQ(plan_arm_view(in).code(), Errc::invalid_argument);
}

}  // namespace
}  // namespace petra::sim
