#include "sim/scene/scene_options.hpp"

#include <cmath>

namespace petra::sim {

const char* boundary_name(Boundary b) {
  return b == Boundary::clear ? "clear" : "weak";
}

const char* shape_name(RockShape s) {
  switch (s) {
    case RockShape::blocky:
      return "blocky";
    case RockShape::rounded:
      return "rounded";
    case RockShape::slab:
      return "slab";
  }
  return "?";
}

Result<Boundary> parse_boundary(std::string_view text) {
  if (text == "clear") return Boundary::clear;
  if (text == "weak") return Boundary::weak;
  return Error::make(Errc::invalid_argument, "boundary: expected clear or weak, got '%.*s'",
                     static_cast<int>(text.size() > 40 ? 40 : text.size()), text.data());
}

Result<RockShape> parse_shape(std::string_view text) {
  if (text == "blocky") return RockShape::blocky;
  if (text == "rounded") return RockShape::rounded;
  if (text == "slab") return RockShape::slab;
  return Error::make(Errc::invalid_argument, "shape: expected blocky, rounded or slab, got '%.*s'",
                     static_cast<int>(text.size() > 40 ? 40 : text.size()), text.data());
}

namespace {

Status in_range(const std::optional<double>& v, double lo, double hi, const char* name,
                const char* unit) {
  if (v && !(std::isfinite(*v) && *v >= lo && *v <= hi))
    return Error::make(Errc::out_of_range, "%s = %g outside %g..%g %s", name, *v, lo, hi, unit);
  return {};
}

Status in_range(double v, double lo, double hi, const char* name, const char* unit) {
  return in_range(std::optional<double>(v), lo, hi, name, unit);
}

Status validate_world(const World& w) {
  PETRA_TRY(in_range(w.relief_rms_mm, 0, kMaxReliefMm, "relief", "mm"));
  PETRA_TRY(in_range(w.pebble_cover, 0, kMaxPebbleCover, "pebbles", "(share of the ground)"));
  PETRA_TRY(in_range(w.stones_per_m2, 0, kMaxStonesPerM2, "stones", "per m^2"));
  PETRA_TRY(in_range(w.slope_deg, 0, kMaxSlopeDeg, "slope", "deg"));
  PETRA_TRY(in_range(w.slope_azimuth_deg, -360, 360, "slope-azimuth", "deg"));
  PETRA_TRY(in_range(w.face_roughness_mm, 0, kMaxFaceRoughnessMm, "face-roughness", "mm"));
  PETRA_TRY(in_range(w.face_curvature_per_m, 0, kMaxFaceCurvaturePerM, "face-curvature", "1/m"));
  PETRA_TRY(in_range(w.gain_left, kMinCameraGain, kMaxCameraGain, "gain-left", ""));
  PETRA_TRY(in_range(w.gain_right, kMinCameraGain, kMaxCameraGain, "gain-right", ""));
  PETRA_TRY(
      in_range(w.offset_left_dn, -kMaxCameraOffsetDn, kMaxCameraOffsetDn, "offset-left", "DN"));
  PETRA_TRY(
      in_range(w.offset_right_dn, -kMaxCameraOffsetDn, kMaxCameraOffsetDn, "offset-right", "DN"));
  PETRA_TRY(in_range(w.vignetting, 0, kMaxVignetting, "vignetting", "(corner fall-off)"));
  PETRA_TRY(in_range(w.prnu, 0, kMaxPrnu, "prnu", "(relative, 1 sigma)"));
  PETRA_TRY(in_range(w.calib_residual_px, 0, kMaxCalibResidualPx, "calib-residual", "px"));
  PETRA_TRY(in_range(w.burial, kMinBurial, kMaxBurial, "burial", "(share of the height)"));
  return {};
}

}  // namespace

World realistic_world() {
  World w;
  w.relief_rms_mm = 2.0;
  w.pebble_cover = 0.12;
  w.stones_per_m2 = 25;
  w.slope_deg = 6;
  w.face_roughness_mm = 0.3;
  w.face_curvature_per_m = 0.5;
  w.gain_right = 0.92;
  w.offset_right_dn = 4;
  w.vignetting = 0.2;
  w.prnu = 0.01;
  w.calib_residual_px = 0.3;
  return w;
}

bool is_clean(const World& w) {
  return w.relief_rms_mm == 0 && w.pebble_cover == 0 && w.stones_per_m2 == 0 && w.slope_deg == 0 &&
         w.face_roughness_mm == 0 && w.face_curvature_per_m == 0 && w.gain_left == 1 &&
         w.gain_right == 1 && w.offset_left_dn == 0 && w.offset_right_dn == 0 &&
         w.vignetting == 0 && w.prnu == 0 && w.calib_residual_px == 0 && !w.burial;
}

Status validate(const SceneOptions& o) {
  if (o.seed > kMaxSeed)
    return Error::make(Errc::out_of_range, "seed = %llu outside 0..%llu",
                       static_cast<unsigned long long>(o.seed),
                       static_cast<unsigned long long>(kMaxSeed));
  if (o.flat_faces && (*o.flat_faces < 2 || *o.flat_faces > 3))
    return Error::make(Errc::out_of_range, "flat-faces = %d: must be 2 or 3", *o.flat_faces);
  PETRA_TRY(in_range(o.sun_elevation_deg, kMinSunElevationDeg, kMaxSunElevationDeg, "sun-elevation",
                     "deg"));
  PETRA_TRY(in_range(o.sun_azimuth_deg, -360, 360, "sun-azimuth", "deg"));
  PETRA_TRY(in_range(o.rock_size_mm, kMinRockSizeMm, kMaxRockSizeMm, "rock-size", "mm"));
  PETRA_TRY(
      in_range(o.rock_distance_mm, kMinRockDistanceMm, kMaxRockDistanceMm, "rock-distance", "mm"));
  PETRA_TRY(
      in_range(o.camera_height_mm, kMinCameraHeightMm, kMaxCameraHeightMm, "camera-height", "mm"));
  if (!(std::isfinite(o.noise_sigma_dn) && o.noise_sigma_dn >= 0 &&
        o.noise_sigma_dn <= kMaxNoiseDn))
    return Error::make(Errc::out_of_range, "noise = %g outside 0..%g DN", o.noise_sigma_dn,
                       kMaxNoiseDn);
  if (o.edge_supersampling < 2 || o.edge_supersampling > 16)
    return Error::make(Errc::out_of_range, "edge supersampling = %d outside 2..16",
                       o.edge_supersampling);
  PETRA_TRY(validate_world(o.world));
  if (o.neighbours < 0 || o.neighbours > kMaxNeighbours)
    return Error::make(Errc::out_of_range, "neighbours = %d outside 0..%d", o.neighbours,
                       kMaxNeighbours);
  if (o.rocks < 1 || o.rocks > kMaxRocks)
    return Error::make(Errc::out_of_range, "rocks = %d outside 1..%d", o.rocks, kMaxRocks);
  if (o.rocks > 1 && (o.neighbours > 0 || o.roi_fill))
    return Error::make(Errc::invalid_argument, "rocks = %d: not with neighbours or roi-fill",
                       o.rocks);
  // The rock must lie ahead of the rig, not below it: its centre sits at most
  // ~150 mm above the ground, so the distance must clearly exceed the height.
  if (o.rock_distance_mm && o.camera_height_mm && *o.camera_height_mm > 0.85 * *o.rock_distance_mm)
    return Error::make(
        Errc::invalid_argument,
        "camera-height %g mm too large for rock-distance %g mm (max 0.85 x distance)",
        *o.camera_height_mm, *o.rock_distance_mm);
  return {};
}

}  // namespace petra::sim
