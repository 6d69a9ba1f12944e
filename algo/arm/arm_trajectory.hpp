// Arm motion planning (docs/method.md section 5): a joint-space move to a standoff
// waypoint out along the grind plane's normal, then a straight approach to
// contact with the tool axis along the negative normal.
//
// JointMove: all joints start and stop together on one trapezoidal time law
// s(t) in [0, 1], scaled so that no joint exceeds its velocity or acceleration
// limit. StraightApproach: the tip moves on the straight line from the standoff
// point to the plane centroid on a trapezoidal law in distance; each sample is
// an exact IK solution (the line is straight in space, not in joint space).
// Both are evaluated at any time t (the executive asks once per control cycle)
// or sampled every dt into a caller buffer of stated size.
// Units: mm, rad, s. World frame as in kinematics.hpp. Memory: no heap; every
// object is fixed-size (JointMove 152 bytes, StraightApproach under 1 kB).
#pragma once

#include <cstddef>
#include <span>

#include "algo/arm/kinematics.hpp"
#include "algo/core/result.hpp"

namespace petra::arm {

// Trapezoidal law on a unit distance: duration, acceleration time, peak rate.
struct UnitProfile {
  double duration_s = 0.0;
  double accel_time_s = 0.0;
  double peak_rate = 0.0;             // 1/s
  double accel = 0.0;                 // 1/s^2
  double position(double t_s) const;  // in [0, 1]
  double rate(double t_s) const;      // 1/s
};
// Time-optimal trapezoid over [0, 1] with rate <= max_rate and |accel| <= max_accel.
UnitProfile unit_profile(double max_rate, double max_accel);

struct JointMove {
  JointVector from = JointVector::Zero();
  JointVector delta = JointVector::Zero();
  UnitProfile profile;
  double duration_s() const { return profile.duration_s; }
  JointVector position_at(double t_s) const;
  JointVector velocity_at(double t_s) const;
};

// `to` must be inside the limits (error names the joint); `from` must be finite.
Result<JointMove> plan_joint_move(const JointVector& from, const JointVector& to,
                                  const JointLimits& limits);

// Samples at t = 0, dt, 2 dt, ... and a last one at the end (exactly `to`).
// Needs joint_move_sample_count(move, dt) entries in `out`; returns that count.
std::size_t joint_move_sample_count(const JointMove& move, double dt_s);
Result<std::size_t> sample_joint_move(const JointMove& move, double dt_s,
                                      std::span<JointVector> out);

// The approach waypoint's distance out along the plane's normal that the
// flight software plans with unless ARM_GOTO says otherwise (its ArmGoal
// default), and that rock proposals judge reachability with.
inline constexpr double kDefaultStandoffMm = 50.0;

struct ApproachRequest {
  Eigen::Vector3d centroid_mm = Eigen::Vector3d::Zero();  // plane centroid, world frame
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();      // unit, out of the rock
  double standoff_mm = kDefaultStandoffMm;                // (0, 500]
  double max_tool_speed_mm_s = 10.0;                      // along the approach line
  double max_tool_accel_mm_s2 = 20.0;
};

enum class ApproachStage : std::uint8_t { request = 0, standoff = 1, contact = 2, path = 3 };
const char* approach_stage_name(ApproachStage stage);

// The straight approach: standoff pose, contact pose and the time law between.
struct StraightApproach {
  ToolTarget standoff;  // tip at centroid + standoff * normal, axis -normal
  ToolTarget contact;   // tip at centroid, axis -normal
  JointVector standoff_q = JointVector::Zero();
  JointVector contact_q = JointVector::Zero();
  double length_mm = 0.0;
  double tool_speed_mm_s = 0.0;  // chosen so that no joint exceeds its limits
  double tool_accel_mm_s2 = 0.0;
  UnitProfile profile;
  double duration_s() const { return profile.duration_s; }
};

struct ApproachPlan {
  IkSolution refusal;                            // reason ok when planned
  ApproachStage stage = ApproachStage::request;  // where a refusal happened
  StraightApproach approach;
  bool ok() const { return refusal.ok(); }
  Error error(const JointLimits& limits) const;  // prefixed with the stage
};

// Checks the standoff, the contact and kPathChecks points between them (each
// must have an IK solution in the limits, continuous with its neighbour), then
// picks the tool speed. `current` is the pose the arm is in (IK branch hint).
inline constexpr int kPathChecks = 64;
ApproachPlan plan_approach(const ArmGeometry& geometry, const JointLimits& limits,
                           const ApproachRequest& request, const JointVector& current);

// Tool target and joint vector at time t of the approach (t clamped to
// [0, duration]); `reverse` walks it from contact back out to the standoff.
ToolTarget approach_target_at(const StraightApproach& approach, double t_s, bool reverse = false);
IkSolution approach_joints_at(const ArmGeometry& geometry, const JointLimits& limits,
                              const StraightApproach& approach, double t_s, const JointVector& hint,
                              bool reverse = false);

std::size_t approach_sample_count(const StraightApproach& approach, double dt_s);
Result<std::size_t> sample_approach(const ArmGeometry& geometry, const JointLimits& limits,
                                    const StraightApproach& approach, double dt_s,
                                    std::span<JointVector> out);

}  // namespace petra::arm
