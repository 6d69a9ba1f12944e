// The ground's picture of a planned grind: the arm in its final (contact) pose
// and at the standoff waypoint, the chosen grind plane with its normal, the
// other planes, the approach line and the ground, in three panels a person can
// read: an oblique 3-D view from beside the arm, the side view in the arm's
// vertical plane (the pitch joints undistorted) and the top view; below them
// the numbers (joint angles, approach speed and time) or the refusal reason.
// Uses the flight planner (algo/arm/arm_trajectory) so the picture shows exactly
// what ARM_GOTO would do.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "algo/arm/arm_trajectory.hpp"
#include "sim/arm/canvas.hpp"
#include "sim/score/planes_file.hpp"

namespace petra::sim {

struct ArmViewInput {
  arm::ArmGeometry geometry = arm::rover_arm_geometry();
  arm::JointLimits limits = arm::default_joint_limits();
  std::vector<OutputPlane> planes;
  std::size_t chosen = 0;
  std::optional<GroundPlane> ground;
  double standoff_mm = arm::kDefaultStandoffMm;
  arm::JointVector start = arm::stow_pose();
};

struct ArmView {
  arm::ApproachPlan plan;
  std::vector<std::string> summary;  // the text under the panels
};

// Plans the approach to the chosen plane; errors only for a bad input
// (no planes, index out of range). A refused plan is a result, not an error.
Result<ArmView> plan_arm_view(const ArmViewInput& input);

// Draws the three panels and the summary on `canvas` (1400 x 900 reads well).
void draw_arm_view(const ArmViewInput& input, const ArmView& view, Canvas& canvas);

}  // namespace petra::sim
