// The realistic ground's relief (docs/scene.md "Realistic world"): a height
// field z = h(x, y) over the local ground plane z = 0, the sum of a fractal
// relief (wavelengths 8..256 mm, tabulated every 2 mm and read back with
// Catmull-Rom interpolation, so heights and slopes are continuous) and
// pebbles (smooth bumps 2..7 mm in radius, one at most per 16 mm cell, exact).
// The relief fades out 1.1..1.4 m from the rock. Rays are marched with a
// Lipschitz bound on the slope, so a pebble is hit like any other surface.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "sim/scene/scene_options.hpp"

namespace petra::sim {

struct Terrain {
  bool active = false;  // false: the flat plane z = 0
  // Fractal relief: heights on a grid of step_mm around `centre`.
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  double step_mm = 2;
  int n = 0;  // grid nodes per side
  std::vector<float> grid;
  double fractal_min = 0, fractal_max = 0;  // bounds of the tabulated relief, mm
  double fractal_slope = 0;                 // bound on its slope
  // Pebbles: at most one per cell, present with probability pebble_chance.
  double pebble_chance = 0;
  std::uint64_t pebble_key = 0;
};

inline constexpr double kPebbleCellMm = 16;
inline constexpr double kPebbleMaxHeightMm = 0.6 * 7;
inline constexpr double kPebbleMaxSlope = 0.95;  // 1.54 x height / radius, height <= 0.6 radius

// Builds the relief for the world's knobs around the rock's ground point.
Terrain make_terrain(const World& world, std::uint64_t seed, const Eigen::Vector2d& centre);

// Height above z = 0 and its gradient at (x, y).
double terrain_height(const Terrain& t, double x, double y, Eigen::Vector2d* gradient = nullptr);
// Upward unit normal at (x, y).
Eigen::Vector3d terrain_normal(const Terrain& t, double x, double y);

// First t in (t_min, t_max] where origin + t*dir meets the height field; false
// when it does not. `origin` must lie above the surface.
bool ray_hits_terrain(const Terrain& t, const Eigen::Vector3d& origin, const Eigen::Vector3d& dir,
                      double t_min, double t_max, double& t_hit);

}  // namespace petra::sim
