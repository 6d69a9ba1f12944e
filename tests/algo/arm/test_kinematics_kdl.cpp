// Forward kinematics against an independent oracle: Orocos KDL's recursive
// solver on a chain built from the same ArmGeometry (docs/arm.md, the chain).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <numbers>
#include <random>
#include <string>

#include "algo/arm/kinematics.hpp"
#include "tests/support/text.hpp"

#ifdef PETRA_HAVE_KDL
#include <kdl/chain.hpp>
#include <kdl/chainfksolverpos_recursive.hpp>
#include <kdl/frames.hpp>
#include <kdl/jntarray.hpp>
#endif

namespace petra::arm {
namespace {

#ifdef PETRA_HAVE_KDL
KDL::Frame to_kdl(const Eigen::Isometry3d& t) {
  const Eigen::Matrix3d& r = t.linear();
  return KDL::Frame(KDL::Rotation(r(0, 0), r(0, 1), r(0, 2), r(1, 0), r(1, 1), r(1, 2), r(2, 0),
                                  r(2, 1), r(2, 2)),
                    KDL::Vector(t.translation().x(), t.translation().y(), t.translation().z()));
}

// The arm as the textbook product of joint rotations and link translations.
KDL::Chain kdl_chain(const ArmGeometry& g) {
  using KDL::Frame;
  using KDL::Joint;
  using KDL::Segment;
  using KDL::Vector;
  KDL::Chain chain;
  chain.addSegment(Segment(Joint(Joint::Fixed), to_kdl(g.world_from_base)));
  chain.addSegment(
      Segment(Joint(Joint::RotZ), Frame(Vector(g.shoulder_offset_mm, 0, g.shoulder_height_mm))));
  // Positive th2 raises the upper arm: a rotation about -y.
  chain.addSegment(Segment(Joint(Joint::RotY, -1.0), Frame(Vector(g.upper_arm_mm, 0, 0))));
  chain.addSegment(Segment(Joint(Joint::RotY, 1.0), Frame(Vector(g.forearm_mm, 0, 0))));
  // th4 is the inner forearm-hand angle: the hand is straight at 180 deg.
  // (KDL takes a segment's tip frame as seen at q = 0, so the joint's offset
  // is put in front of the link.)
  const Joint wrist(Joint::RotY, 1.0, -std::numbers::pi);
  chain.addSegment(Segment(wrist, wrist.pose(0.0) * Frame(Vector(g.hand_mm, 0, 0))));
  // Roll, then the grinder across the hand: tool z = -hand z, tip tool_mm along it.
  chain.addSegment(Segment(Joint(Joint::RotX),
                           Frame(KDL::Rotation::RotX(std::numbers::pi), Vector(0, 0, -g.tool_mm))));
  return chain;
}

ArmGeometry random_geometry(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  ArmGeometry g;
  g.shoulder_height_mm = 150 + 100 * u(rng);
  g.shoulder_offset_mm = 40 * u(rng);
  g.upper_arm_mm = 320 + 100 * u(rng);
  g.forearm_mm = 280 + 100 * u(rng);
  g.hand_mm = 90 + 50 * u(rng);
  g.tool_mm = 80 + 50 * u(rng);
  const Eigen::Vector3d axis = Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized();
  g.world_from_base = Eigen::Translation3d(500 * u(rng), 500 * u(rng), 500 * u(rng)) *
                      Eigen::AngleAxisd(std::numbers::pi * u(rng), axis);
  return g;
}

TEST(KinematicsKdl, ForwardKinematicsMatchesKdlOn10000RandomJointVectors) {
  std::mt19937_64 rng(20240611);
  std::uniform_real_distribution<double> angle(-std::numbers::pi, std::numbers::pi);
  double worst_mm = 0.0;
  double worst_rot = 0.0;
  for (int geometry_index = 0; geometry_index < 10; ++geometry_index) {
    const ArmGeometry g = geometry_index == 0 ? ArmGeometry{} : random_geometry(rng);
    ASSERT_TRUE(validate_geometry(g).ok());
    const KDL::Chain chain = kdl_chain(g);
    ASSERT_EQ(chain.getNrOfJoints(), 5u);
    KDL::ChainFkSolverPos_recursive solver(chain);
    KDL::JntArray q_kdl(5);
    for (int i = 0; i < 1000; ++i) {
      JointVector q;
      for (int j = 0; j < kJointCount; ++j) q[j] = angle(rng);
      for (int j = 0; j < kJointCount; ++j) q_kdl(j) = q[j];
      KDL::Frame f;
      ASSERT_GE(solver.JntToCart(q_kdl, f), 0);
      const Eigen::Isometry3d mine = tool_frame(g, q);
      const ToolPose pose = forward_kinematics(g, q);
      for (int r = 0; r < 3; ++r) {
        worst_mm = std::max(worst_mm, std::abs(mine.translation()[r] - f.p(r)));
        worst_mm = std::max(worst_mm, std::abs(pose.tip_mm[r] - f.p(r)));
        worst_rot = std::max(worst_rot, std::abs(pose.axis[r] - f.M(r, 2)));
        for (int c = 0; c < 3; ++c)
          worst_rot = std::max(worst_rot, std::abs(mine.linear()(r, c) - f.M(r, c)));
      }
    }
  }
  RecordProperty("worst_position_mm", test::sci(worst_mm));
  RecordProperty("worst_rotation", test::sci(worst_rot));
  EXPECT_LT(worst_mm, 1e-9);
  EXPECT_LT(worst_rot, 1e-9);
}

TEST(KinematicsKdl, StowPoseIsTheFoldedZ) {
  // At (0, 0, 145, 35, 0) deg: upper arm forward, forearm folded back and down,
  // hand forward again, tool pointing down. Checked against KDL, not against us.
  const ArmGeometry g;
  // The solver keeps a reference to its chain: the chain must outlive it (a
  // temporary here dangles; -O2 turned that into JntToCart returning -4).
  const KDL::Chain chain = kdl_chain(g);
  KDL::ChainFkSolverPos_recursive solver(chain);
  KDL::JntArray q_kdl(5);
  const JointVector q = stow_pose();
  for (int j = 0; j < kJointCount; ++j) q_kdl(j) = q[j];
  KDL::Frame f;
  ASSERT_GE(solver.JntToCart(q_kdl, f), 0);
  EXPECT_NEAR(f.M(2, 2), -1.0, 1e-12);  // tool axis straight down
  const double c = std::cos(145.0 * std::numbers::pi / 180.0);
  const double s = std::sin(145.0 * std::numbers::pi / 180.0);
  EXPECT_NEAR(f.p.x(), g.shoulder_offset_mm + g.upper_arm_mm + c * g.forearm_mm + g.hand_mm, 1e-9);
  EXPECT_NEAR(f.p.z(), g.shoulder_height_mm - s * g.forearm_mm - g.tool_mm, 1e-9);
}
#else
TEST(KinematicsKdl, ForwardKinematicsMatchesKdlOn10000RandomJointVectors) {
  GTEST_SKIP() << "skipped: Orocos KDL not available in this build (cross build)";
}
TEST(KinematicsKdl, StowPoseIsTheFoldedZ) {
  GTEST_SKIP() << "skipped: Orocos KDL not available in this build (cross build)";
}
#endif

}  // namespace
}  // namespace petra::arm
