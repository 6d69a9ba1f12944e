#include "algo/arm/kinematics.hpp"

#include <gtest/gtest.h>

#include <numbers>
#include <random>
#include <string>

#include "tests/support/angles.hpp"
#include "tests/support/heap_counter.hpp"
#include "tests/support/text.hpp"

namespace petra::arm {
namespace {

JointVector random_in_limits(std::mt19937_64& rng, const JointLimits& l) {
  JointVector q;
  for (int j = 0; j < kJointCount; ++j) {
    q[j] = std::uniform_real_distribution<double>(l.min_rad[j], l.max_rad[j])(rng);
  }
  return q;
}

ArmGeometry mounted_geometry() {
  // Base 300 mm right of and 1.2 m below a camera-like world origin, turned 20 deg.
  ArmGeometry g;
  g.world_from_base = Eigen::Translation3d(300, -200, -1200) *
                      Eigen::AngleAxisd(20 * test::kRadPerDeg, Eigen::Vector3d::UnitZ()) *
                      Eigen::AngleAxisd(3 * test::kRadPerDeg, Eigen::Vector3d::UnitX());
  return g;
}

double angle_between(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

TEST(Kinematics, DefaultsAreTheSeedRangesAndPose) {
  const JointLimits l = default_joint_limits();
  EXPECT_TRUE(validate_limits(l).ok());
  EXPECT_TRUE(validate_geometry(ArmGeometry{}).ok());
  const double lo[] = {0, 0, 0, 35, -45};
  const double hi[] = {90, 90, 145, 180, 45};
  for (int j = 0; j < kJointCount; ++j) {
    EXPECT_DOUBLE_EQ(l.min_rad[j], lo[j] * test::kRadPerDeg);
    EXPECT_DOUBLE_EQ(l.max_rad[j], hi[j] * test::kRadPerDeg);
  }
  EXPECT_TRUE((stow_pose() - test::joints_deg(0, 0, 145, 35, 0)).norm() < 1e-15);
  EXPECT_EQ(first_joint_outside(l, stow_pose()), -1);
}

TEST(Kinematics, ReachIsAboutEightHundredMillimetres) {
  // Arm stretched horizontally forward, tool pointing down (th4 = 180: hand straight).
  const ArmGeometry g;
  const ToolPose p = forward_kinematics(g, test::joints_deg(0, 0, 0, 180, 0));
  EXPECT_NEAR(p.tip_mm.x(), 40 + 320 + 280 + 90, 1e-9);
  EXPECT_NEAR(p.tip_mm.z(), 150 - 80, 1e-9);
  EXPECT_NEAR(p.axis.z(), -1.0, 1e-12);
}

TEST(Kinematics, IkThenFkReturnsTheTargetEverywhereInTheLimits) {
  const JointLimits l = default_joint_limits();
  std::mt19937_64 rng(7);
  double worst_mm = 0.0;
  double worst_rad = 0.0;
  int solved = 0;
  for (const ArmGeometry& g : {ArmGeometry{}, mounted_geometry()}) {
    for (int i = 0; i < 5000; ++i) {
      const JointVector q = random_in_limits(rng, l);
      const ToolPose target = forward_kinematics(g, q);
      // Hint: somewhere else in the limits, so the solver cannot just echo it.
      const IkSolution s =
          inverse_kinematics(g, l, {target.tip_mm, target.axis}, random_in_limits(rng, l));
      ASSERT_TRUE(s.ok()) << "i=" << i << " " << s.error(l).message;
      EXPECT_EQ(first_joint_outside(l, s.q, 0.0), -1);
      const ToolPose back = forward_kinematics(g, s.q);
      worst_mm = std::max(worst_mm, (back.tip_mm - target.tip_mm).norm());
      worst_rad = std::max(worst_rad, angle_between(back.axis, target.axis));
      ++solved;
    }
  }
  RecordProperty("worst_tip_error_mm", test::sci(worst_mm));
  RecordProperty("worst_axis_error_rad", test::sci(worst_rad));
  EXPECT_EQ(solved, 10000);
  EXPECT_LT(worst_mm, 1e-6);
  EXPECT_LT(worst_rad, 1e-6);
}

TEST(Kinematics, IkPrefersTheBranchNearestTheHint) {
  // Within the joint ranges of docs/method.md 5 the solution is unique, so IK must give back
  // the very joint vector the target came from.
  const ArmGeometry g;
  const JointLimits l = default_joint_limits();
  std::mt19937_64 rng(11);
  for (int i = 0; i < 1000; ++i) {
    const JointVector q = random_in_limits(rng, l);
    const ToolPose t = forward_kinematics(g, q);
    const IkSolution s = inverse_kinematics(g, l, {t.tip_mm, t.axis}, stow_pose());
    ASSERT_TRUE(s.ok());
    EXPECT_LT((s.q - q).cwiseAbs().maxCoeff(), 1e-7) << "i=" << i;
  }
}

TEST(Kinematics, ElbowDownBranchIsFoundWhenTheLimitsAllowIt) {
  // Widen th3 to negative angles: the same target then has two elbow branches;
  // the hint selects which one.
  const ArmGeometry g;
  JointLimits l = default_joint_limits();
  l.min_rad[1] = -90 * test::kRadPerDeg;
  l.min_rad[2] = -145 * test::kRadPerDeg;
  l.min_rad[3] = -90 * test::kRadPerDeg;
  l.max_rad[3] = 270 * test::kRadPerDeg;
  const JointVector up = test::joints_deg(30, 40, 60, 120, 10);
  const ToolPose t = forward_kinematics(g, up);
  const IkSolution a = inverse_kinematics(g, l, {t.tip_mm, t.axis}, up);
  ASSERT_TRUE(a.ok());
  EXPECT_LT((a.q - up).norm(), 1e-9);
  // Elbow down: th2 = 40 - 2 atan2(a3 sin 60, a2 + a3 cos 60) = -15.6 deg, th4 = 184.4 deg.
  const JointVector down_hint = test::joints_deg(30, -15, -60, 184, 10);
  const IkSolution b = inverse_kinematics(g, l, {t.tip_mm, t.axis}, down_hint);
  ASSERT_TRUE(b.ok());
  EXPECT_LT(b.q[2], 0.0);
  const ToolPose tb = forward_kinematics(g, b.q);
  EXPECT_LT((tb.tip_mm - t.tip_mm).norm(), 1e-9);
  EXPECT_LT(angle_between(tb.axis, t.axis), 1e-9);
}

TEST(Kinematics, TargetsBeyondReachAreRefused) {
  const ArmGeometry g;
  const JointLimits l = default_joint_limits();
  // Tool straight down, 2 m in front of the base: far too far.
  const IkSolution s = inverse_kinematics(g, l, {{2000, 100, 0}, {0, 0, -1}}, stow_pose());
  EXPECT_EQ(s.reason, ArmReason::beyond_reach);
  EXPECT_GT(s.value, 1000.0);
  EXPECT_EQ(s.error(l).code, Errc::no_solution);
  // Just past full stretch (tool down, hand straight): 1 mm beyond.
  const ToolPose stretched = forward_kinematics(g, test::joints_deg(20, 0, 0, 180, 0));
  const Eigen::Vector3d out =
      stretched.tip_mm +
      Eigen::Vector3d(std::cos(20 * test::kRadPerDeg), std::sin(20 * test::kRadPerDeg), 0);
  const IkSolution s2 = inverse_kinematics(g, l, {out, stretched.axis}, stow_pose());
  EXPECT_EQ(s2.reason, ArmReason::beyond_reach);
  EXPECT_NEAR(s2.value, 1.0, 1e-6);
}

TEST(Kinematics, TargetsInsideTheMinimumReachAreRefused) {
  // Wrist right at the shoulder: closer than |upper arm - forearm| = 40 mm.
  const ArmGeometry g;
  const JointLimits l = default_joint_limits();
  const Eigen::Vector3d shoulder(g.shoulder_offset_mm, 0, g.shoulder_height_mm);
  // Hand horizontal forward (tool down): hand end = wrist + 90 mm x; tip 80 mm below.
  const Eigen::Vector3d tip = shoulder + Eigen::Vector3d(g.hand_mm, 10, -g.tool_mm);
  const IkSolution s = inverse_kinematics(g, l, {tip, {0, 0, -1}}, stow_pose());
  EXPECT_EQ(s.reason, ArmReason::inside_reach);
  EXPECT_GT(s.value, 0.0);
}

TEST(Kinematics, TargetsOutsideAJointRangeNameThatJoint) {
  const ArmGeometry g;
  const JointLimits l = default_joint_limits();
  struct Case {
    JointVector q;  // the pose that would reach the target, with one joint out of range
    int joint;
  };
  const Case cases[] = {
      {test::joints_deg(-20, 30, 60, 120, 0), 1},   // behind the base's right side
      {test::joints_deg(100, 30, 60, 120, 0), 1},   // past 90 deg to the left
      {test::joints_deg(30, -20, 30, 150, 0), 2},   // upper arm below horizontal
      {test::joints_deg(30, 80, 160, 120, 0), 3},   // elbow folded past 145
      {test::joints_deg(30, 40, 60, 20, 0), 4},     // wrist folded tighter than 35
      {test::joints_deg(30, 40, 60, 120, 60), 5},   // tool tilted 60 deg out of the arm plane
      {test::joints_deg(30, 40, 60, 120, -50), 5},  // and the other way
  };
  for (const Case& c : cases) {
    const ToolPose t = forward_kinematics(g, c.q);
    const IkSolution s = inverse_kinematics(g, l, {t.tip_mm, t.axis}, stow_pose());
    EXPECT_EQ(s.reason, ArmReason::joint_limit) << "joint " << c.joint;
    EXPECT_EQ(s.joint, c.joint);
    EXPECT_NEAR(s.value, c.q[c.joint - 1], 1e-9) << "joint " << c.joint;
    const Error e = s.error(l);
    EXPECT_EQ(e.code, Errc::out_of_range);
    char expected[8];
    std::snprintf(expected, sizeof expected, "th%d =", c.joint);
    EXPECT_NE(std::string(e.message).find(expected), std::string::npos) << e.message;
  }
}

TEST(Kinematics, BadTargetsAreRefusedAndNamed) {
  const ArmGeometry g;
  const JointLimits l = default_joint_limits();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const ToolTarget bad[] = {{{nan, 0, 0}, {0, 0, -1}},
                            {{400, 100, 0}, {0, 0, -2}},
                            {{400, 100, 0}, {0, 0, 0}},
                            {{400, 100, 0}, {nan, 0, 1}}};
  for (const ToolTarget& t : bad) {
    const IkSolution s = inverse_kinematics(g, l, t, stow_pose());
    EXPECT_EQ(s.reason, ArmReason::bad_target);
    EXPECT_EQ(s.error(l).code, Errc::invalid_argument);
  }
}

TEST(Kinematics, ATargetOnTheYawAxisKeepsTheHintsYaw) {
  // Hand end right above the base (th1 undefined): any yaw works; keep the hint's.
  const ArmGeometry g;
  const JointLimits l = default_joint_limits();
  const JointVector q = test::joints_deg(0, 80, 120, 130, 0);
  // Move the shoulder back by the hand end's radius: the hand end is then on the axis.
  const double r = arm_skeleton(g, q).points_mm[4].x();
  ArmGeometry g2 = g;
  g2.shoulder_offset_mm -= r;
  const ArmSkeleton sk2 = arm_skeleton(g2, q);
  ASSERT_NEAR(std::hypot(sk2.points_mm[4].x(), sk2.points_mm[4].y()), 0.0, 1e-9);
  JointVector hint = q;
  hint[0] = 37 * test::kRadPerDeg;
  const ToolPose t = forward_kinematics(g2, hint);
  const IkSolution s = inverse_kinematics(g2, l, {t.tip_mm, t.axis}, hint);
  ASSERT_TRUE(s.ok()) << s.error(l).message;
  EXPECT_NEAR(s.q[0], 37 * test::kRadPerDeg, 1e-9);
  const ToolPose back = forward_kinematics(g2, s.q);
  EXPECT_LT((back.tip_mm - t.tip_mm).norm(), 1e-9);
}

TEST(Kinematics, ValidationNamesTheField) {
  ArmGeometry g;
  g.forearm_mm = 0;
  auto s = validate_geometry(g);
  ASSERT_FALSE(s.ok());
  EXPECT_NE(std::string(s.error().message).find("forearm_mm"), std::string::npos);
  g = ArmGeometry{};
  g.world_from_base.linear() << 1, 0, 0, 0, 2, 0, 0, 0, 1;
  EXPECT_EQ(validate_geometry(g).code(), Errc::not_orthonormal);
  JointLimits l = default_joint_limits();
  l.max_velocity_rad_s[2] = 0;
  s = validate_limits(l);
  ASSERT_FALSE(s.ok());
  EXPECT_NE(std::string(s.error().message).find("th3"), std::string::npos);
  l = default_joint_limits();
  l.min_rad[4] = 1.0;
  l.max_rad[4] = -1.0;
  EXPECT_EQ(validate_limits(l).code(), Errc::invalid_argument);
}

TEST(Kinematics, NoHeap) {
  const ArmGeometry g = mounted_geometry();
  const JointLimits l = default_joint_limits();
  const ToolPose t = forward_kinematics(g, test::joints_deg(30, 40, 60, 120, 10));
  test::HeapScope scope;
  double sink = 0.0;
  for (int i = 0; i < 100; ++i) {
    const IkSolution s = inverse_kinematics(g, l, {t.tip_mm, t.axis}, stow_pose());
    sink +=
        s.q.sum() + tool_frame(g, s.q).translation().x() + arm_skeleton(g, s.q).points_mm[5].z();
    sink += static_cast<double>(s.error(l).code);
  }
  EXPECT_EQ(scope.allocations(), 0u);
  EXPECT_TRUE(std::isfinite(sink));
}

}  // namespace
}  // namespace petra::arm
