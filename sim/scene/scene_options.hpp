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
// Realistic-world knobs (World below).
inline constexpr double kMaxReliefMm = 10, kMaxPebbleCover = 0.25, kMaxStonesPerM2 = 200;
inline constexpr double kMaxSlopeDeg = 20, kMaxFaceRoughnessMm = 2, kMaxFaceCurvaturePerM = 5;
inline constexpr double kMinCameraGain = 0.5, kMaxCameraGain = 1.5, kMaxCameraOffsetDn = 40;
inline constexpr double kMinBurial = 0.15, kMaxBurial = 0.7;
inline constexpr double kMaxVignetting = 0.6, kMaxPrnu = 0.05, kMaxCalibResidualPx = 2;
inline constexpr int kMaxNeighbours = 3;
inline constexpr int kMaxRocks = 6;  // multi-rock scenes: 2..kMaxRocks full rocks
// Seeds stay exact as JSON numbers (doubles): 0 .. 2^53 - 1.
inline constexpr std::uint64_t kMaxSeed = (std::uint64_t{1} << 53) - 1;

// The realistic world (docs/scene.md "Realistic world"). Every knob at 0 (or
// gain 1) is today's clean world, rendered byte for byte as before;
// realistic_world() gives each knob its realistic default (`--real`).
struct World {
  double relief_rms_mm = 0;  // terrain height field, wavelengths 8..256 mm
  double pebble_cover = 0;   // share of the ground under pebbles (height field, 2..7 mm)
  double stones_per_m2 = 0;  // small convex stones, 10..40 mm, within 0.6 m of the rock
  double slope_deg = 0;      // ground under the rock against the rover's level
  std::optional<double> slope_azimuth_deg;  // uphill direction from the heading (drawn)
  double face_roughness_mm = 0;             // RMS of the rock faces' relief, wavelengths 2.5..20 mm
  double face_curvature_per_m = 0;          // faces bulge with this curvature (1/radius)
  double gain_left = 1, gain_right = 1;     // per-camera gain on the DN
  double offset_left_dn = 0, offset_right_dn = 0;
  double vignetting = 0;         // relative fall-off at the image corners
  double prnu = 0;               // pixel response non-uniformity, 1 sigma, relative
  double calib_residual_px = 0;  // RMS reprojection error of calib.json against the true rig
  std::optional<double> burial;  // share of the rock's height below the ground (drawn 0.15..0.35)
};
World realistic_world();
bool is_clean(const World& w);

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
  World world;                  // clean unless set (realistic_world())
  // The operator's hard cases (docs/scene.md "Neighbours and a rock filling the ROI").
  int neighbours = 0;     // further rocks touching the target, 0..kMaxNeighbours
  bool roi_fill = false;  // truth ROI inside the rock's silhouette: no ground in it
  // Multi-rock scenes (docs/scene.md "Several rocks"): 1 = the one rock of
  // every other scene; 2..kMaxRocks = further full rocks over the ground in
  // view, some not grindable or not reachable by design.
  int rocks = 1;
};

// Errors name the option and its valid range.
Status validate(const SceneOptions& options);

}  // namespace petra::sim
