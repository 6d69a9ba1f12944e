// A synthetic scene: the stereo rig, one convex rock partly sunk into flat
// ground, the sun, the surface materials and the sensor. World frame: ground
// frame, z up, ground plane z = 0, origin on the ground below the rig
// midpoint, y roughly along the cameras' heading (docs/scene.md).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "algo/camera/camera_model.hpp"
#include "algo/camera/rectify_geometry.hpp"
#include "algo/core/result.hpp"
#include "sim/scene/convex_rock.hpp"
#include "sim/scene/face_relief.hpp"
#include "sim/scene/scene_options.hpp"
#include "sim/scene/terrain.hpp"
#include "sim/scene/texture.hpp"

namespace petra::sim {

inline constexpr int kImageWidth = 1024;
inline constexpr int kImageHeight = 768;

// Why a further rock of a multi-rock scene is there: the kind it was drawn
// as (its truth flags are computed, scene_rocks.hpp; drawing keeps a rock
// only when they agree).
enum class RockKind { grindable, too_small, too_rough, out_of_reach };
inline constexpr int kRockKinds = 4;
const char* rock_kind_name(RockKind kind);

struct Scene {
  SceneOptions options;  // as given
  // Resolved choices (drawn or given).
  Boundary boundary = Boundary::clear;
  RockShape shape = RockShape::blocky;
  int flat_faces = 2;
  double sun_elevation_deg = 45;
  double sun_azimuth_deg = 180;  // from the rig-to-rock heading, counter-clockwise from above
  double rock_size_mm = 150;
  double rock_distance_mm = 700;
  double camera_height_mm = 550;

  StereoRig rig;
  ConvexRock rock;
  Eigen::Vector3d rock_centre_mm = Eigen::Vector3d::Zero();  // centre of the rock's ellipsoid
  Eigen::Vector3d sun_dir = Eigen::Vector3d::UnitZ();        // unit, from the scene toward the sun
  double ambient = 0.3;       // sky irradiance relative to the sun's at normal incidence
  double sky_radiance = 1.0;  // what a ray that misses the ground sees
  double tone_ratio = 1.0;    // rock's mean brightness / the ground's, as the left camera sees them
  TextureRecipe ground;
  TextureRecipe rock_surface;
  double gain_dn = 200;  // DN per unit radiance (exposure)
  int attempts = 1;      // placements tried before one met every requirement

  // The realistic world (all inactive for a clean scene). Rendering happens
  // in the local frame above (ground z = 0 under the rock); calib.json and
  // truth.json are in the rover's world frame, X_world = world_R (X - pivot) + pivot,
  // which differs from it when the ground is sloped.
  Terrain terrain;
  FaceRelief face_relief;
  std::vector<ConvexRock> stones;
  std::vector<double> stone_albedo;      // relative to the ground's
  std::vector<ConvexRock> neighbours;    // rocks touching the target (options.neighbours)
  std::vector<double> neighbour_albedo;  // relative to the target's
  std::vector<double> neighbour_gap_mm;  // slid back this far from first contact
  // Multi-rock scenes (options.rocks >= 2): the further rocks are neighbours
  // 1.. (rock k is neighbours[k - 1]), each with its own rough faces and the
  // kind it was drawn as; empty otherwise (plain polyhedra, as before).
  std::vector<FaceRelief> neighbour_relief;
  std::vector<RockKind> neighbour_kind;
  bool tilted = false;
  Eigen::Matrix3d world_R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d pivot = Eigen::Vector3d::Zero();
  double slope_azimuth_deg = 0;  // uphill, from the heading, counter-clockwise
  StereoRig true_rig_world;      // the rendering rig in the world frame
  StereoRig calib_rig;           // what calib.json says (== true_rig_world when exact)
  double calib_residual_px = 0;  // RMS |calib - true| reprojection, as measured
};

// True when the geometry is the clean world's (flat ground, planar faces, one rock).
inline bool clean_geometry(const Scene& s) {
  return !s.terrain.active && !s.face_relief.active && s.stones.empty() && s.neighbours.empty();
}
// World frame <-> the local rendering frame.
inline Eigen::Vector3d to_world(const Scene& s, const Eigen::Vector3d& p) {
  return s.tilted ? Eigen::Vector3d(s.world_R * (p - s.pivot) + s.pivot) : p;
}
inline Eigen::Vector3d dir_to_world(const Scene& s, const Eigen::Vector3d& d) {
  return s.tilted ? Eigen::Vector3d(s.world_R * d) : d;
}

// Rock r of the scene: 0 the target, k >= 1 neighbours[k - 1]; its faces' relief.
inline const ConvexRock& rock_at(const Scene& s, int r) {
  return r == 0 ? s.rock : s.neighbours[static_cast<std::size_t>(r - 1)];
}
inline int rock_count(const Scene& s) {
  return 1 + static_cast<int>(s.neighbours.size());
}
const FaceRelief& relief_at(const Scene& s, int r);

// Builds the scene for options.seed and the options; deterministic. Fails
// with a message naming the option when the options are invalid or no
// placement meets the requirements (rock and shadow in both views, flat faces
// visible and larger than every other facet).
Result<Scene> make_scene(const SceneOptions& options);

// True when every point lies 40 px inside both original images and half
// that inside both rectified images (`pair`: the rig's rectification).
bool in_both_views(const Scene& scene, const RectifiedPair& pair,
                   const std::vector<Eigen::Vector3d>& points);

// Camera's ray angle per pixel (mm on a surface 1 mm away, at normal incidence).
inline double pixel_angle(const TsaiCamera& cam) {
  return cam.dy_mm / cam.f_mm;
}

}  // namespace petra::sim
