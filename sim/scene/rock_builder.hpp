// The rock's shape: an ellipsoid-like convex polyhedron cut by many small
// planes (the rough faces) and by 2 or 3 deep planes facing the cameras (the
// large, truly flat grind-plane candidates), then partly sunk into the ground.
#pragma once

#include <Eigen/Core>
#include <optional>

#include "algo/core/result.hpp"
#include "sim/scene/convex_rock.hpp"
#include "sim/scene/rng.hpp"
#include "sim/scene/scene_options.hpp"

namespace petra::sim {

struct RockSpec {
  RockShape shape = RockShape::blocky;
  double size_mm = 150;  // largest dimension (the two farthest vertices), buried part included
  int flat_faces = 2;
  Eigen::Vector3d toward_cameras = Eigen::Vector3d::UnitZ();  // unit, rock to rig midpoint
  std::optional<double> burial;  // share of the height below the ground (default: drawn 0.15..0.35)
};

struct BuiltRock {
  ConvexRock rock;  // ellipsoid centre at (0, 0, centre_height_mm), ground at z = 0
  double centre_height_mm = 0;
};

// Draws the shape from `rng`. The rock is sunk by 15..35 % of its height.
Result<BuiltRock> build_rock(Rng& rng, const RockSpec& spec);

}  // namespace petra::sim
