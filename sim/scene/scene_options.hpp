// What a caller may choose about a synthetic scene. Everything left unset is
// drawn from the seed; a value that is set replaces its draw without shifting
// any other draw, so e.g. changing the sun keeps the rock (docs/scene.md).
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

#include "algo/core/result.hpp"

namespace petra::sim {

// The two cases the paper distinguishes: a rock whose tone differs clearly
// from the ground, and one of nearly the same tone (weak boundary).
enum class Boundary { clear, weak };
// blocky: few large facets; rounded: many small facets; slab: flat and wide.
enum class RockShape { blocky, rounded, slab };

const char* boundary_name(Boundary b);
const char* shape_name(RockShape s);
Result<Boundary> parse_boundary(std::string_view text);
Result<RockShape> parse_shape(std::string_view text);

// Documented ranges (validate() enforces them).
inline constexpr double kMinSunElevationDeg = 10, kMaxSunElevationDeg = 80;
inline constexpr double kMinRockSizeMm = 80, kMaxRockSizeMm = 250;
inline constexpr double kMinRockDistanceMm = 500, kMaxRockDistanceMm = 900;
inline constexpr double kMinCameraHeightMm = 400, kMaxCameraHeightMm = 700;
inline constexpr double kMaxNoiseDn = 20;
// Seeds stay exact as JSON numbers (doubles): 0 .. 2^53 - 1.
inline constexpr std::uint64_t kMaxSeed = (std::uint64_t{1} << 53) - 1;

struct SceneOptions {
  std::uint64_t seed = 1;
  std::optional<Boundary> boundary;
  std::optional<RockShape> shape;
  std::optional<int> flat_faces;            // grind-plane candidates, 2 or 3
  std::optional<double> sun_elevation_deg;  // above the horizon
  std::optional<double> sun_azimuth_deg;    // from the cameras' heading, counter-clockwise
                                            // seen from above; 180 = behind the cameras
  std::optional<double> rock_size_mm;       // largest dimension of the rock
  std::optional<double> rock_distance_mm;   // rig midpoint to rock centre
  std::optional<double> camera_height_mm;   // rig midpoint above the ground
  double noise_sigma_dn = 1.5;  // sensor noise at mid-grey (128 DN), grows with the signal
  bool texture = true;          // false: uniform albedo (geometry tests only)
  int edge_supersampling = 8;   // samples per axis in pixels crossed by an edge
};

// Errors name the option and its valid range.
Status validate(const SceneOptions& options);

}  // namespace petra::sim
