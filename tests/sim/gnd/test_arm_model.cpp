// The ground station's arm: drawn from joint angles with the flight
// kinematics, and the plan for a picked plane as the arm service makes it.
#include "sim/gnd/arm_model.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include "algo/core/json_reader.hpp"

namespace petra::gnd {
namespace {

constexpr std::array<double, 5> kStow{0, 0, 145, 35, 0};

TEST(ArmModel, SkeletonTipIsTheForwardKinematicsTip) {
  const ArmModel model;
  const std::array<double, 5> q_deg{32.6, 11.4, 62.2, 113.9, -7.7};
  const std::string s = model.skeleton_json(q_deg);
  std::vector<json::Token> tokens(128);
  auto doc = json::Document::parse(s, tokens);
  ASSERT_TRUE(doc.ok());
  ASSERT_EQ(doc->token(0).count, 6u);  // base .. tip
  const std::uint32_t tip = doc->element(0, 5);
  arm::JointVector q;
  for (int k = 0; k < 5; ++k) q[k] = q_deg[static_cast<std::size_t>(k)] * std::numbers::pi / 180.0;
  const auto fk = arm::forward_kinematics(model.geometry(), q);
  for (std::uint32_t k = 0; k < 3; ++k)
    EXPECT_NEAR(doc->token(doc->element(tip, k)).number, fk.tip_mm[static_cast<int>(k)], 1e-6);
}

TEST(ArmModel, PlanPutsTheContactTipOnTheCentroid) {
  const ArmModel model;
  // Plane 0 of simulated scene seed 1 (the ground station e2e test).
  auto plan = model.plan_json(
      R"({"centroid_mm":[-35.0,643.8,44.0],"normal":[0.029,-0.294,0.955],"standoff_mm":50})",
      kStow);
  ASSERT_TRUE(plan.ok());
  EXPECT_NE(plan->find("\"ok\":true"), std::string::npos) << *plan;
  const std::size_t contact = plan->find("\"contact\"");
  ASSERT_NE(contact, std::string::npos);
  const std::string tip = plan->substr(plan->find("\"tip_mm\":[", contact) + 10);
  double x = 0, y = 0, z = 0;
  ASSERT_EQ(std::sscanf(tip.c_str(), "%lf,%lf,%lf", &x, &y, &z), 3);
  EXPECT_NEAR(x, -35.0, 1e-6);
  EXPECT_NEAR(y, 643.8, 1e-6);
  EXPECT_NEAR(z, 44.0, 1e-6);
}

TEST(ArmModel, AnUnreachablePlaneIsRefusedWithTheReason) {
  const ArmModel model;
  auto plan = model.plan_json(
      R"({"centroid_mm":[-35.0,3000.0,44.0],"normal":[0,0,1],"standoff_mm":50})", kStow);
  ASSERT_TRUE(plan.ok());
  EXPECT_NE(plan->find("\"ok\":false"), std::string::npos) << *plan;
  EXPECT_NE(plan->find("reach"), std::string::npos) << *plan;
}

TEST(ArmModel, MalformedRequestsNameTheField) {
  const ArmModel model;
  const std::pair<const char*, const char*> cases[] = {
      {"not json", "not JSON"},
      {R"({"normal":[0,0,1],"standoff_mm":50})", "centroid_mm: missing"},
      {R"({"centroid_mm":[0,0],"normal":[0,0,1],"standoff_mm":50})", "centroid_mm: expected"},
      {R"({"centroid_mm":[0,0,"a"],"normal":[0,0,1],"standoff_mm":50})", "centroid_mm[2]"},
      {R"({"centroid_mm":[0,500,0],"normal":[0,0,2],"standoff_mm":50})", "normal: length"},
      {R"({"centroid_mm":[0,500,0],"normal":[0,0,1],"standoff_mm":400})", "standoff_mm"},
      {R"({"centroid_mm":[0,500,0],"normal":[0,0,1]})", "standoff_mm: missing"},
  };
  for (const auto& [body, why] : cases) {
    auto r = model.plan_json(body, kStow);
    ASSERT_FALSE(r.ok()) << body;
    EXPECT_NE(std::string(r.error().message).find(why), std::string::npos)
        << body << " -> " << r.error().message;
  }
}

TEST(ArmModel, MountParsesAsPetraFswArmMount) {
  auto g = parse_arm_mount("300,100,100,90");
  ASSERT_TRUE(g.ok());
  EXPECT_TRUE(g->world_from_base.isApprox(arm::default_rover_mount(), 1e-12));
  for (const char* bad : {"", "1,2,3", "1,2,3,4,5", "1,2,x,4", "1,2,3,1e6"})
    EXPECT_FALSE(parse_arm_mount(bad).ok()) << bad;
}

}  // namespace
}  // namespace petra::gnd
