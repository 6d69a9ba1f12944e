#include "algo/arm/arm_trajectory.hpp"

#include <gtest/gtest.h>

#include <array>
#include <numbers>
#include <vector>

#include "tests/support/angles.hpp"
#include "tests/support/heap_counter.hpp"

namespace petra::arm {
namespace {

// Largest |dq/dt| and |d2q/dt2| per joint from samples dt apart, relative to the limits.
struct RateUse {
  double velocity = 0.0;  // max over joints of |v| / v_max
  double accel = 0.0;
};
RateUse rate_use(const std::vector<JointVector>& q, double dt, const JointLimits& l) {
  RateUse r;
  for (std::size_t k = 1; k + 1 < q.size(); ++k) {
    for (int j = 0; j < kJointCount; ++j) {
      const double v = (q[k + 1][j] - q[k][j]) / dt;
      const double a = (q[k + 1][j] - 2 * q[k][j] + q[k - 1][j]) / (dt * dt);
      r.velocity = std::max(r.velocity, std::abs(v) / l.max_velocity_rad_s[j]);
      r.accel = std::max(r.accel, std::abs(a) / l.max_acceleration_rad_s2[j]);
    }
  }
  return r;
}

TEST(ArmTrajectory, UnitProfileIsTrapezoidOrTriangle) {
  const UnitProfile trap = unit_profile(0.5, 1.0);  // 0.5 s to cruise, cruise 1.5 s
  EXPECT_NEAR(trap.duration_s, 2.5, 1e-12);
  EXPECT_NEAR(trap.position(trap.duration_s / 2), 0.5, 1e-12);
  EXPECT_NEAR(trap.rate(1.0), 0.5, 1e-12);
  EXPECT_EQ(trap.position(-1.0), 0.0);
  EXPECT_EQ(trap.position(10.0), 1.0);
  const UnitProfile tri = unit_profile(10.0, 4.0);  // never reaches 10/s
  EXPECT_NEAR(tri.duration_s, 1.0, 1e-12);
  EXPECT_NEAR(tri.peak_rate, 2.0, 1e-12);
  EXPECT_NEAR(tri.position(0.5), 0.5, 1e-12);
}

TEST(ArmTrajectory, JointMoveIsSynchronisedAndWithinLimits) {
  const JointLimits l = default_joint_limits();
  const JointVector from = stow_pose();
  const JointVector to = test::joints_deg(40, 50, 70, 130, -20);
  auto move = plan_joint_move(from, to, l);
  ASSERT_TRUE(move.ok()) << move.error().message;
  const double dt = 0.001;
  std::vector<JointVector> q(joint_move_sample_count(*move, dt));
  auto n = sample_joint_move(*move, dt, q);
  ASSERT_TRUE(n.ok());
  EXPECT_EQ(*n, q.size());
  EXPECT_LT((q.front() - from).norm(), 1e-15);
  EXPECT_LT((q.back() - to).norm(), 1e-15);
  const RateUse use = rate_use(q, dt, l);
  EXPECT_LE(use.velocity, 1.0 + 1e-6);
  EXPECT_LE(use.accel, 1.0 + 1e-3);
  // Time-optimal for the slowest joint: it runs at its limit.
  EXPECT_GT(std::max(use.velocity, use.accel), 0.99);
  // The largest move (th4, 95 deg at 30 deg/s, 60 deg/s^2) sets the time: 95/30 + 30/60 s.
  EXPECT_NEAR(move->duration_s(), 95.0 / 30.0 + 0.5, 1e-9);
  // Synchronised: every joint is at the same fraction of its move at all times.
  for (std::size_t k = 0; k < q.size(); k += 97) {
    const JointVector frac = (q[k] - from).cwiseQuotient(to - from);
    EXPECT_LT(frac.maxCoeff() - frac.minCoeff(), 1e-12);
  }
}

TEST(ArmTrajectory, JointMoveRefusesAGoalOutsideTheLimitsAndASmallBuffer) {
  const JointLimits l = default_joint_limits();
  auto bad = plan_joint_move(stow_pose(), test::joints_deg(10, 10, 150, 90, 0), l);
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.code(), Errc::out_of_range);
  EXPECT_NE(std::string(bad.error().message).find("th3"), std::string::npos);
  auto move = plan_joint_move(stow_pose(), test::joints_deg(10, 10, 100, 90, 0), l);
  ASSERT_TRUE(move.ok());
  std::array<JointVector, 8> small;
  EXPECT_EQ(sample_joint_move(*move, 0.01, small).code(), Errc::capacity_exceeded);
  EXPECT_EQ(sample_joint_move(*move, 0.0, small).code(), Errc::non_positive);
  auto still = plan_joint_move(stow_pose(), stow_pose(), l);
  ASSERT_TRUE(still.ok());
  EXPECT_EQ(still->duration_s(), 0.0);
  auto one = sample_joint_move(*still, 0.01, small);
  ASSERT_TRUE(one.ok());
  EXPECT_EQ(*one, 1u);
}

// A plane the arm can reach: the tool pose at `q` read as (centroid, -normal).
ApproachRequest request_from_pose(const ArmGeometry& g, const JointVector& q, double standoff) {
  const ToolPose p = forward_kinematics(g, q);
  ApproachRequest r;
  r.centroid_mm = p.tip_mm;
  r.normal = -p.axis;
  r.standoff_mm = standoff;
  return r;
}

TEST(ArmTrajectory, ApproachIsAStraightLineAlongTheNormalWithinJointLimits) {
  const ArmGeometry g;
  const JointLimits l = default_joint_limits();
  for (const JointVector& contact :
       {test::joints_deg(30, 40, 100, 120, 10), test::joints_deg(60, 20, 90, 150, -30),
        test::joints_deg(10, 60, 130, 100, 40)}) {
    const ApproachRequest req = request_from_pose(g, contact, 80.0);
    const ApproachPlan plan = plan_approach(g, l, req, stow_pose());
    ASSERT_TRUE(plan.ok()) << plan.error(l).message;
    const StraightApproach& a = plan.approach;
    EXPECT_LT(
        (forward_kinematics(g, a.standoff_q).tip_mm - (req.centroid_mm + 80.0 * req.normal)).norm(),
        1e-6);
    const double dt = 0.002;
    std::vector<JointVector> q(approach_sample_count(a, dt));
    auto n = sample_approach(g, l, a, dt, q);
    ASSERT_TRUE(n.ok()) << n.error().message;
    double off_line = 0.0;
    double off_axis = 0.0;
    for (const JointVector& qk : q) {
      const ToolPose p = forward_kinematics(g, qk);
      const Eigen::Vector3d rel = p.tip_mm - req.centroid_mm;
      off_line = std::max(off_line, (rel - rel.dot(req.normal) * req.normal).norm());
      off_axis = std::max(off_axis, std::acos(std::clamp(-p.axis.dot(req.normal), -1.0, 1.0)));
      EXPECT_EQ(first_joint_outside(l, qk), -1);
    }
    EXPECT_LT(off_line, 1e-6);
    EXPECT_LT(off_axis, 1e-6);
    EXPECT_LT((forward_kinematics(g, q.back()).tip_mm - req.centroid_mm).norm(), 1e-6);
    const RateUse use = rate_use(q, dt, l);
    EXPECT_LE(use.velocity, 1.0) << "tool speed " << a.tool_speed_mm_s;
    EXPECT_LE(use.accel, 1.0) << "tool accel " << a.tool_accel_mm_s2;
    EXPECT_LE(a.tool_speed_mm_s, req.max_tool_speed_mm_s);
    // Reverse: from contact back out to the standoff.
    const ToolTarget back = approach_target_at(a, 0.0, true);
    EXPECT_LT((back.tip_mm - req.centroid_mm).norm(), 1e-12);
  }
}

TEST(ArmTrajectory, UnreachablePlanesAreRefusedWithStageAndReason) {
  const ArmGeometry g;
  const JointLimits l = default_joint_limits();
  ApproachRequest far;
  far.centroid_mm = {1500, 300, -200};
  far.normal = {0, 0, 1};
  ApproachPlan p = plan_approach(g, l, far, stow_pose());
  EXPECT_EQ(p.stage, ApproachStage::standoff);
  EXPECT_EQ(p.refusal.reason, ArmReason::beyond_reach);
  EXPECT_NE(std::string(p.error(l).message).find("approach standoff"), std::string::npos);

  // A face tilted 60 deg sideways from the arm plane: the hand roll (th5) cannot follow.
  ApproachRequest tilted = request_from_pose(g, test::joints_deg(45, 40, 100, 120, 0), 50);
  const Eigen::Vector3d side(-std::sin(45 * test::kRadPerDeg), std::cos(45 * test::kRadPerDeg), 0);
  tilted.normal =
      (std::cos(60 * test::kRadPerDeg) * tilted.normal + std::sin(60 * test::kRadPerDeg) * side)
          .normalized();
  p = plan_approach(g, l, tilted, stow_pose());
  EXPECT_EQ(p.refusal.reason, ArmReason::joint_limit);
  EXPECT_EQ(p.refusal.joint, 5);

  ApproachRequest bad = request_from_pose(g, test::joints_deg(45, 40, 100, 120, 0), 0.0);
  EXPECT_EQ(plan_approach(g, l, bad, stow_pose()).stage, ApproachStage::request);
  bad.standoff_mm = 50;
  bad.normal *= 2.0;
  p = plan_approach(g, l, bad, stow_pose());
  EXPECT_EQ(p.stage, ApproachStage::request);
  EXPECT_EQ(p.refusal.reason, ArmReason::bad_target);
}

TEST(ArmTrajectory, APathThatLeavesTheLimitsMidwayIsRefused) {
  // The tool axis leans 0.8 sideways across the 45 deg azimuth. While the hand end
  // sweeps from 15 to 75 deg azimuth, the roll needed is asin(0.8 cos(th1 - 45)):
  // 44 deg at both ends, 53 deg in the middle. Both ends are fine, the path is not.
  const ArmGeometry g;
  const JointLimits l = default_joint_limits();
  const Eigen::Vector3d across(-std::sin(45 * test::kRadPerDeg), std::cos(45 * test::kRadPerDeg),
                               0);
  const Eigen::Vector3d axis = 0.8 * across + Eigen::Vector3d(0, 0, -0.6);
  const double radius = 300;
  const double length = 2 * radius * std::tan(30 * test::kRadPerDeg) / 0.8;
  const Eigen::Vector3d middle_hand(radius * std::cos(45 * test::kRadPerDeg),
                                    radius * std::sin(45 * test::kRadPerDeg), 120);
  ApproachRequest req;
  req.normal = -axis;
  req.centroid_mm = middle_hand + 0.5 * length * axis + g.tool_mm * axis;
  req.standoff_mm = length;
  ASSERT_TRUE(inverse_kinematics(g, l, {req.centroid_mm, axis}, stow_pose()).ok());
  ASSERT_TRUE(
      inverse_kinematics(g, l, {req.centroid_mm + length * req.normal, axis}, stow_pose()).ok());
  const ApproachPlan p = plan_approach(g, l, req, stow_pose());
  EXPECT_EQ(p.stage, ApproachStage::path);
  EXPECT_EQ(p.refusal.reason, ArmReason::joint_limit);
  EXPECT_EQ(p.refusal.joint, 5);
}

TEST(ArmTrajectory, NoHeap) {
  const ArmGeometry g;
  const JointLimits l = default_joint_limits();
  const ApproachRequest req = request_from_pose(g, test::joints_deg(30, 40, 100, 120, 10), 60.0);
  std::array<JointVector, 4096> buffer;
  test::HeapScope scope;
  const ApproachPlan plan = plan_approach(g, l, req, stow_pose());
  auto move = plan_joint_move(stow_pose(), plan.approach.standoff_q, l);
  auto n1 = sample_joint_move(*move, 0.02, buffer);
  auto n2 = sample_approach(g, l, plan.approach, 0.02, buffer);
  EXPECT_EQ(scope.allocations(), 0u);
  EXPECT_TRUE(plan.ok() && move.ok() && n1.ok() && n2.ok());
}

}  // namespace
}  // namespace petra::arm
