// Stereo calibration from chessboard views (ground tool; the paper's section
// 3.1 for a rig): each camera alone (camera_calibration), the right camera's
// pose relative to the left from every pair seen by both (rotations averaged,
// translations by median), then one joint refinement of both cameras'
// intrinsics, the rig pose and every board pose (calib_bundle). The result
// is a calib.json rig with the world frame at the left camera (R = I, T = 0)
// or, on request, on the board of the first pair used.
#pragma once

#include <Eigen/Core>
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "algo/camera/camera_model.hpp"
#include "algo/core/result.hpp"
#include "sim/calib/camera_calibration.hpp"

namespace petra::calib {

// Corners of one stereo pair, row-major (chessboard_corners order); empty
// when the board was not found in that image.
struct StereoPairCorners {
  std::string left_name, right_name;
  std::vector<Eigen::Vector2d> left_uv, right_uv;
};

struct StereoCalibOptions {
  int cols = 9, rows = 6;  // inner corners
  double square_mm = 1;    // lengths in calib.json come out in these units
  TsaiCamera left_sensor;  // width, height, dx, dy
  TsaiCamera right_sensor;
  CameraCalibOptions camera;     // per camera
  bool world_at_target = false;  // world = board of the first pair used
  int min_pairs = 3;
};

struct StereoCalibration {
  StereoRig rig;
  CameraCalibration left_alone, right_alone;      // each camera on its own
  std::vector<int> pairs;                         // input pairs in the joint fit
  std::vector<double> left_rms_px, right_rms_px;  // per input pair, joint model; < 0 if unused
  double left_rms_px_all = 0, right_rms_px_all = 0;
  double rms_px = 0;       // over every corner of both cameras
  double baseline_mm = 0;  // distance between the optical centres
  std::array<double, kIntrinsicCount> left_sigma{}, right_sigma{};
  std::vector<std::string> notes;
  int world_pair = -1;  // pair whose board is the world, or -1
};

Result<StereoCalibration> calibrate_stereo(const std::vector<StereoPairCorners>& pairs,
                                           const StereoCalibOptions& options);

}  // namespace petra::calib
