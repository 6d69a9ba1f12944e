// Kinematics of the 5-joint sampling arm (docs/method.md section 5, docs/arm.md).
//
// Joints: th1 shoulder base yaw (about the base's vertical z axis), th2 upper arm
// pitch, th3 forearm pitch, th4 wrist pitch, th5 hand roll (about the hand's long
// axis). The grinder is mounted across the hand: its axis is perpendicular to the
// roll axis, so rolling the hand tilts the tool out of the arm's vertical plane.
// That gives the 5 joints control of the 5 task constraints (tip point + tool
// axis direction) and a closed-form inverse (docs/arm.md has the derivation).
//
// In the arm's vertical plane, with link angles measured up from the horizontal:
//   upper arm  alpha1 = th2
//   forearm    alpha2 = th2 - th3          (th3 bends the elbow down)
//   hand       alpha3 = alpha2 + pi - th4  (th4 is the inner forearm-hand angle)
//   tool axis  cos(th5) * (sin a3, -cos a3 in the plane) + sin(th5) * (plane normal, left)
//
// Units: millimetres and radians. Frames: `world` is the camera calibration's
// world frame (calib.json); `base` is the arm's base frame (x forward, z up along
// the yaw axis), placed in the world by ArmGeometry::world_from_base.
// Memory: no heap; every type here is fixed-size. No I/O.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <numbers>

#include "algo/core/result.hpp"

namespace petra::arm {

inline constexpr int kJointCount = 5;
inline constexpr double kRadPerDeg = std::numbers::pi / 180.0;  // joint angles are radians
using JointVector = Eigen::Matrix<double, kJointCount, 1>;

// Link lengths (mm) and the mount. Defaults: about 0.8 m reach (docs/arm.md).
struct ArmGeometry {
  double shoulder_height_mm = 150.0;  // d1: base to shoulder pitch axis, along the yaw axis
  double shoulder_offset_mm = 40.0;   // a1: yaw axis to shoulder pitch axis, forward
  double upper_arm_mm = 320.0;        // a2: shoulder to elbow
  double forearm_mm = 280.0;          // a3: elbow to wrist
  double hand_mm = 90.0;              // wrist pitch axis to the tool axis, along the hand
  double tool_mm = 80.0;              // hand axis to grinder tip, along the tool axis
  Eigen::Isometry3d world_from_base = Eigen::Isometry3d::Identity();
};

// Where the arm sits on the rover, in Petra's world frame for the arm: the
// rover ground frame (z up, origin on the ground below the stereo rig's
// midpoint, y forward along the cameras' heading; the simulated scenes use
// it). Base at (300, 100, 100) mm: right front corner, low; base x along +y,
// so th1 = 0..90 deg sweeps from straight ahead to the left (docs/arm.md).
Eigen::Isometry3d default_rover_mount();
// ArmGeometry defaults with that mount.
ArmGeometry rover_arm_geometry();

// Joint ranges and rate limits, per joint (index 0 is th1).
struct JointLimits {
  std::array<double, kJointCount> min_rad{};
  std::array<double, kJointCount> max_rad{};
  std::array<double, kJointCount> max_velocity_rad_s{};
  std::array<double, kJointCount> max_acceleration_rad_s2{};
};

// Ranges of docs/method.md 5: th1 0..90, th2 0..90, th3 0..145, th4 35..180, th5 -45..45 deg;
// rates 30 deg/s and 60 deg/s^2 for every joint.
JointLimits default_joint_limits();
// The paper's initial (stowed) pose (0, 0, 145, 35, 0) deg.
JointVector stow_pose();

Status validate_geometry(const ArmGeometry& geometry);
Status validate_limits(const JointLimits& limits);

// Grinder tip and tool axis (unit; points from the hand into the work), world frame.
struct ToolPose {
  Eigen::Vector3d tip_mm = Eigen::Vector3d::Zero();
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
};

// Tool frame in the world: origin at the tip, z along the tool axis, x along the
// hand's roll axis.
Eigen::Isometry3d tool_frame(const ArmGeometry& geometry, const JointVector& q);
ToolPose forward_kinematics(const ArmGeometry& geometry, const JointVector& q);

// The arm's joint centres in the world, for drawing and collision checks:
// base, shoulder, elbow, wrist, hand end (on the tool axis), tip.
struct ArmSkeleton {
  std::array<Eigen::Vector3d, 6> points_mm{};
};
ArmSkeleton arm_skeleton(const ArmGeometry& geometry, const JointVector& q);

// Why a pose was refused. Stable numbers: they go into telemetry (docs/icd.md).
enum class ArmReason : std::uint8_t {
  ok = 0,
  bad_target = 1,    // non-finite point, or an axis that is not a unit vector
  beyond_reach = 2,  // wrist farther from the shoulder than upper arm + forearm
  inside_reach = 3,  // wrist closer to the shoulder than |upper arm - forearm|
  joint_limit = 4,   // joint `joint` (1..5) would leave its range
  path_blocked = 5,  // a point of a planned straight path is unreachable
  bad_request = 6,   // a planning parameter is outside its domain
};
const char* arm_reason_name(ArmReason reason);

// Which joint check failed, or why the target is unreachable. value: the joint
// angle that left its range (rad), or by how much the reach was missed (mm).
struct IkSolution {
  ArmReason reason = ArmReason::ok;
  int joint = 0;  // 1..5 with joint_limit, else 0
  double value = 0.0;
  JointVector q = JointVector::Zero();

  bool ok() const { return reason == ArmReason::ok; }
  // A message naming the joint or the limit ("th3 = 151.20 deg outside 0..145 deg").
  Error error(const JointLimits& limits) const;
};

struct ToolTarget {
  Eigen::Vector3d tip_mm = Eigen::Vector3d::Zero();  // world frame
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();   // unit, world frame
};

// Joint angles placing the tip at target.tip_mm with the tool axis along
// target.axis. Closed form: up to 4 branches (th1 and th1 + pi, elbow up and
// down); among those inside the limits, the one closest to `hint` (e.g. the
// current pose) wins. A target on the yaw axis keeps hint's th1. When no branch
// fits, the reason of the branch that came closest is returned. Exact to
// rounding (about 1e-12 mm); no iteration.
IkSolution inverse_kinematics(const ArmGeometry& geometry, const JointLimits& limits,
                              const ToolTarget& target, const JointVector& hint);

// Index (0-based) of the first joint outside its range by more than
// tolerance_rad, or -1.
int first_joint_outside(const JointLimits& limits, const JointVector& q,
                        double tolerance_rad = 1e-9);

}  // namespace petra::arm
