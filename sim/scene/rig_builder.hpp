// The stereo rig: a Bumblebee2-like pair (1024x768, 4.65 um pixels, f ~3.8 mm,
// 150 mm baseline, barrel distortion) with small per-seed errors in every
// intrinsic and in each camera's mounting, aimed down at the ground.
#pragma once

#include <Eigen/Core>

#include "algo/camera/camera_model.hpp"
#include "sim/scene/rng.hpp"

namespace petra::sim {

struct RigPose {
  Eigen::Vector3d midpoint_mm;  // world position of the midpoint between the cameras
  double heading_rad = 0;  // yaw: 0 looks along +y, positive turns toward -x (counter-clockwise)
  double tilt_rad = 0.6;   // optical axes below the horizon
  double roll_rad = 0;     // about the optical axis
};

// Draws the intrinsics and per-camera misalignments from `rng`.
StereoRig build_rig(Rng& rng, const RigPose& pose);

}  // namespace petra::sim
