#include "algo/propose/arm_reach.hpp"

namespace petra {

ArmReach::ArmReach(const arm::ArmGeometry& geometry, const arm::JointLimits& limits,
                   const arm::JointVector& current, double standoff_mm)
    : geometry_(&geometry), limits_(&limits), current_(current), standoff_mm_(standoff_mm) {}

arm::ArmReason ArmReach::why(const Eigen::Vector3d& point_mm, const Eigen::Vector3d& normal) const {
  arm::ApproachRequest a;
  a.centroid_mm = point_mm;
  a.normal = normal;
  a.standoff_mm = standoff_mm_;
  return arm::plan_approach(*geometry_, *limits_, a, current_).refusal.reason;
}

bool ArmReach::reaches(const Eigen::Vector3d& centre_mm, const Eigen::Vector3d& normal) const {
  return why(centre_mm, normal) == arm::ArmReason::ok;
}

}  // namespace petra
