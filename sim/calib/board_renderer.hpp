// Synthetic views of a plane through a Tsai camera (ground tool): calibration
// boards for the calibration tests and demos, textured planes for the click
// transfer tests. Each pixel averages n x n jittered sub-samples whose rays (exact
// inverse of the camera model, distortion included) meet the plane z = 0 of
// the world frame; then optional Gaussian blur and noise. The camera's R, T
// are the plane's pose (world = plane frame).
#pragma once

#include <cstdint>
#include <functional>

#include "algo/camera/camera_model.hpp"
#include "sim/io/image_io.hpp"

namespace petra::calib {

struct BoardSpec {
  int cols = 9;  // inner corners; corner (i, j) at (i, j, 0) * square_mm
  int rows = 6;
  double square_mm = 25;
  double margin_mm = 12;  // white border around the outer squares
};

struct RenderOptions {
  int supersample = 4;       // n x n jittered sub-samples per pixel
  double blur_sigma_px = 0;  // Gaussian blur after sampling
  double noise_sigma = 0;    // Gaussian noise, gray levels
  double background = 110;   // where the ray misses the plane's albedo
  std::uint64_t seed = 1;
};

// Gray level of a plane point, or a negative value for "not on the object".
using Albedo = std::function<double(double x_mm, double y_mm)>;

io::GrayImage render_plane(const TsaiCamera& camera, const Albedo& albedo,
                           const RenderOptions& options);

// Chessboard albedo: 30 on dark squares, 220 on bright squares and the
// margin. The square between corners (0,0), (1,0), (0,1), (1,1) is dark
// (chessboard_corners' ordering convention).
Albedo chessboard_albedo(const BoardSpec& board);

// World position of inner corner (i, j).
Eigen::Vector3d board_corner(const BoardSpec& board, int i, int j);

}  // namespace petra::calib
