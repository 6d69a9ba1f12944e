// The arm as the ground station draws it: the same kinematics as the flight
// arm service (algo/arm/kinematics, algo/arm/arm_trajectory) with the mount petra-fsw
// is configured with, so the page's arm model follows ARM_STATUS joint
// angles and a picked plane shows the pose the arm will plan for it.
//   skeleton_json(joints): [[x,y,z] x 6] mm, world frame: base, shoulder,
//     elbow, wrist, hand end, grinder tip (arm::arm_skeleton)
//   plan_json(request, current): the approach plan_approach() makes from the
//     current joints, or the refusal with its reason (as ARM_GOTO would).
#pragma once

#include <array>
#include <string>
#include <string_view>

#include "algo/arm/arm_trajectory.hpp"
#include "algo/arm/kinematics.hpp"
#include "algo/core/result.hpp"

namespace petra::gnd {

// "x,y,z,yaw_deg" (petra-fsw's arm.mount) -> the rover geometry at that mount.
Result<arm::ArmGeometry> parse_arm_mount(std::string_view text);

class ArmModel {
 public:
  explicit ArmModel(const arm::ArmGeometry& geometry = arm::rover_arm_geometry());

  // {"mount_mm":[..],"yaw_deg":..,"links_mm":{..},"limits_deg":{"min":[..],"max":[..]},
  //  "stow_deg":[..],"stow":<skeleton>}
  std::string geometry_json() const;
  std::string skeleton_json(const std::array<double, arm::kJointCount>& joint_deg) const;

  // Request body: {"centroid_mm":[x,y,z],"normal":[a,b,c],"standoff_mm":S}
  // (normal within 1 % of unit length, standoff 5..300 mm as ARM_GOTO).
  // Answer: {"ok":true,"standoff":{"joint_deg":[..],"skeleton":..,"tip_mm":[..]},
  //          "contact":{..},"length_mm":..,"duration_s":..}
  //     or  {"ok":false,"stage":"contact","reason":"th3 = ... outside ..."}.
  // A malformed request is an error naming the field.
  Result<std::string> plan_json(std::string_view body,
                                const std::array<double, arm::kJointCount>& current_deg) const;

  const arm::ArmGeometry& geometry() const { return geometry_; }

 private:
  arm::ArmGeometry geometry_;
  arm::JointLimits limits_;
};

}  // namespace petra::gnd
