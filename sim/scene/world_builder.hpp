// The realistic world's parts that are added to a placed scene
// (docs/scene.md "Realistic world"): the sloped ground's frame, the relief,
// the stones, the rough faces and the calibration that differs from the
// cameras that render the images. Each draws from its own random stream, so
// the clean scene of the same seed keeps its rock, rig and sun.
#pragma once

#include <Eigen/Core>

#include "sim/scene/rng.hpp"
#include "sim/scene/scene.hpp"

namespace petra::sim {

// Local ground frame from the rover's world frame for a slope rising along
// the direction `uphill_azimuth_rad` (counter-clockwise from +y) about the
// rock's ground point: fills world_R, pivot and tilted.
void set_slope(Scene& scene, double slope_deg, double uphill_azimuth_rad);

// The rig as built (world frame) moved into the local frame.
StereoRig rig_to_local(const Scene& scene, const StereoRig& world_rig);
// The local rig expressed in the world frame.
StereoRig rig_to_world(const Scene& scene, const StereoRig& local_rig);

// Relief, stones and rough faces for the scene's world knobs (after placement).
void add_world_geometry(Scene& scene);

// calib.json's rig: the true rig (world frame) with a random small error in
// both cameras' rotations and the right camera's principal point and focal
// length, scaled so the RMS reprojection difference over the visible scene
// is options.world.calib_residual_px. Fills calib_rig, true_rig_world and
// calib_residual_px (measured).
void set_calibration(Scene& scene);

// RMS over scene points (world) of |project(a) - project(b)| in both cameras, px.
double reprojection_rms_px(const StereoRig& a, const StereoRig& b,
                           const std::vector<Eigen::Vector3d>& world_points);
// World points the left camera sees on a coarse pixel grid (sky left out).
std::vector<Eigen::Vector3d> visible_world_points(const Scene& scene, int step_px);

}  // namespace petra::sim
