// The arm's geometry in the rover's world frame as fsw.json places it: the
// flight defaults (algo/arm rover_arm_geometry) with arm.mount when given.
// The arm service and the proposer's reach both use it. Apart from the
// configuration's parser, which knows nothing of the arm's kinematics.
#pragma once

#include "algo/arm/kinematics.hpp"
#include "fsw/config.hpp"

namespace petra::fsw {

::petra::arm::ArmGeometry arm_geometry(const FswConfig& config);

}  // namespace petra::fsw
