#include "sim/scene/scene_set.hpp"

namespace petra::sim {

namespace {

// Entry k's boundary x sun elevation x shape x flat faces (all 8 boundary x
// sun pairs, three times in 24 entries).
SceneOptions cycle_entry(int k) {
  static constexpr double kSunElevationsDeg[4] = {20, 35, 50, 65};
  SceneOptions o;
  o.boundary = k % 2 == 0 ? Boundary::clear : Boundary::weak;
  o.sun_elevation_deg = kSunElevationsDeg[(k / 2) % 4];
  o.shape = static_cast<RockShape>(k % 3);
  o.flat_faces = 2 + (k / 3) % 2;
  return o;
}

}  // namespace

std::vector<SceneOptions> standard_scene_set() {
  std::vector<SceneOptions> set;
  for (int k = 0; k < kStandardSetSize; ++k) {
    SceneOptions o = cycle_entry(k);
    o.seed = 1000 + static_cast<std::uint64_t>(k);
    set.push_back(o);
  }
  return set;
}

std::vector<SceneOptions> real_scene_set() {
  static constexpr double kReliefMm[4] = {1.0, 2.0, 3.0, 4.0};
  static constexpr double kSlopeDeg[4] = {0, 5, 10, 15};
  static constexpr double kGainRight[4] = {0.85, 0.92, 1.0, 1.1};
  static constexpr double kOffsetRightDn[4] = {-6, 4, 8, 0};
  static constexpr double kResidualPx[3] = {0.2, 0.3, 0.4};
  static constexpr double kRoughnessMm[3] = {0.2, 0.3, 0.5};
  static constexpr double kCurvaturePerM[3] = {0.3, 0.6, 1.0};
  std::vector<SceneOptions> set;
  for (int k = 0; k < kRealSetSize; ++k) {
    SceneOptions& o = set.emplace_back(cycle_entry(k));
    o.seed = 2000 + static_cast<std::uint64_t>(k);
    World& w = o.world;
    w = realistic_world();
    w.relief_rms_mm = kReliefMm[k % 4];
    w.slope_deg = kSlopeDeg[(k / 4) % 4];
    w.pebble_cover = k % 2 == 0 ? 0.08 : 0.15;
    w.stones_per_m2 = 10.0 + 10.0 * (k % 3);
    w.face_roughness_mm = kRoughnessMm[k % 3];
    w.face_curvature_per_m = kCurvaturePerM[(k / 3) % 3];
    w.gain_right = kGainRight[(k / 2) % 4];
    w.offset_right_dn = kOffsetRightDn[(k / 5) % 4];
    w.vignetting = 0.1 + 0.1 * (k % 3);
    w.calib_residual_px = kResidualPx[(k / 8) % 3];
    o.noise_sigma_dn = 2.0;
    o.edge_supersampling = 4;  // pebble shadows make many edge pixels
    // The operator's hard cases: rocks touching the target, then a rock
    // that fills the ROI.
    if (k >= kRealBaseSize && k < kRealBaseSize + 4) o.neighbours = 1 + k % 2;
    if (k >= kRealBaseSize + 4) o.roi_fill = true;
  }
  return set;
}

std::vector<SceneOptions> multi_rock_scene_set() {
  std::vector<SceneOptions> set;
  for (int k = 0; k < kMultiSetSize; ++k) {
    SceneOptions& o = set.emplace_back(cycle_entry(k));
    o.seed = 3000 + static_cast<std::uint64_t>(k);
    o.world = realistic_world();
    o.noise_sigma_dn = 2.0;
    o.edge_supersampling = 4;
    o.rocks = 3 + k % 4;
  }
  return set;
}

}  // namespace petra::sim
