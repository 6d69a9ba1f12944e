// The arm's reach as the chain asks it: whether the grinder, coming along a
// plane's normal to a point, has an approach plan (algo/arm/arm_trajectory
// plan_approach: the standoff waypoint, the contact and the straight path
// between, every pose within the joint limits). The footprint search asks
// it per disc (algo/surface/grind_footprint DiscReach); the proposer per
// plane. One definition, so a proposal and the SELECT_ROI that repeats it
// judge reach alike. Fixed size; no heap; the geometry and limits are the
// caller's and must outlive it.
#pragma once

#include "algo/arm/arm_trajectory.hpp"
#include "algo/arm/kinematics.hpp"
#include "algo/surface/grind_footprint.hpp"

namespace petra {

class ArmReach final : public DiscReach {
 public:
  // current: the arm's pose now (the IK branch hint); standoff_mm as ARM_GOTO's.
  ArmReach(const arm::ArmGeometry& geometry, const arm::JointLimits& limits,
           const arm::JointVector& current, double standoff_mm);

  // ok, or why the plan fails (the first refusal along the approach).
  arm::ArmReason why(const Eigen::Vector3d& point_mm, const Eigen::Vector3d& normal) const;
  bool reaches(const Eigen::Vector3d& centre_mm, const Eigen::Vector3d& normal) const override;

 private:
  const arm::ArmGeometry* geometry_;
  const arm::JointLimits* limits_;
  arm::JointVector current_;
  double standoff_mm_;
};

}  // namespace petra
