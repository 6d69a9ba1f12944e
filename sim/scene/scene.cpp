#include "sim/scene/scene.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <utility>
#include <vector>

#include "algo/camera/rectify_geometry.hpp"
#include "sim/scene/further_rocks.hpp"
#include "sim/scene/neighbours.hpp"
#include "sim/scene/rig_builder.hpp"
#include "sim/scene/rng.hpp"
#include "sim/scene/rock_builder.hpp"
#include "sim/scene/scene_geometry.hpp"
#include "sim/scene/terrain.hpp"
#include "sim/scene/world_builder.hpp"

namespace petra::sim {

namespace {

constexpr double kDeg = M_PI / 180.0;
// Independent random streams of one seed.
constexpr std::uint64_t kStreamChoices = 1;
constexpr std::uint64_t kStreamGeometry = 2;
constexpr std::uint64_t kStreamMaterials = 3;
constexpr std::uint64_t kStreamWorld = 4;
constexpr double kMinSunOverSlopeDeg = 5;  // sun above the sloped ground by at least this
constexpr double kMinRigOverGroundMm = 200;
constexpr int kMaxAttempts = 300;
constexpr double kMarginPx = 40;         // rock and shadow this far inside both images
constexpr double kMaxViewAngleDeg = 70;  // flat faces seen at most this obliquely
constexpr double kMinFlatSeparationDeg = 25;
constexpr double kFlatOverRoughArea = 1.5;     // a flat face is this much larger than any other
constexpr double kMinFlatAreaFraction = 0.05;  // of size^2

// Choices drawn once per seed, each replaced by its option when given.
void resolve_choices(const SceneOptions& o, Scene& s) {
  Rng pick(o.seed, kStreamChoices);
  const bool clear = pick.coin();
  s.boundary = o.boundary.value_or(clear ? Boundary::clear : Boundary::weak);
  const int shape = pick.integer(0, 2);
  s.shape = o.shape.value_or(static_cast<RockShape>(shape));
  s.flat_faces = o.flat_faces.value_or(pick.integer(2, 3));
  s.sun_elevation_deg = o.sun_elevation_deg.value_or(pick.uniform(15, 70));
  const double side = pick.coin() ? 1.0 : -1.0;
  s.sun_azimuth_deg = o.sun_azimuth_deg.value_or(side * pick.uniform(100, 145));
  s.rock_size_mm = o.rock_size_mm.value_or(pick.uniform(90, 240));
  const double distance = pick.uniform(520, 820);
  const double height_u = pick.uniform();
  s.rock_distance_mm = o.rock_distance_mm.value_or(distance);
  if (o.camera_height_mm && !o.rock_distance_mm)
    s.rock_distance_mm = std::max(s.rock_distance_mm, *o.camera_height_mm / 0.85);
  const double h_max = std::min(kMaxCameraHeightMm, 0.85 * s.rock_distance_mm);
  s.camera_height_mm =
      o.camera_height_mm.value_or(kMinCameraHeightMm + height_u * (h_max - kMinCameraHeightMm));
}

void choose_materials(const SceneOptions& o, Scene& s) {
  Rng m(o.seed, kStreamMaterials);
  s.ambient = m.uniform(0.22, 0.35);
  TextureRecipe& g = s.ground;
  g.mean_albedo = m.uniform(0.35, 0.5);
  g.fractal_contrast = 0.2;
  g.largest_mm = 48;
  g.finest_mm = 1.5;
  g.persistence = 0.8;
  g.spot_scale_mm = 6;
  g.spot_contrast = 0.22;
  g.vein_scale_mm = 0;
  g.perm = make_permutation(mix64(o.seed * 2 + 0x1000));
  const bool darker = m.coin();
  const double dark_factor = m.uniform(0.5, 0.65);
  const double light_factor = m.uniform(1.35, 1.55);
  const double weak_factor = m.uniform(0.94, 1.06);
  TextureRecipe& r = s.rock_surface;
  if (s.boundary == Boundary::weak) {
    // Same tone and the same kind of texture: only geometry tells them apart.
    r = g;
    s.tone_ratio = weak_factor;
  } else {
    s.tone_ratio = darker ? dark_factor : light_factor;
    r.fractal_contrast = 0.17;
    r.largest_mm = 32;
    r.finest_mm = 1.2;
    r.persistence = 0.8;
    r.spot_scale_mm = 4;
    r.spot_contrast = 0.2;
    r.vein_scale_mm = 30;
    r.vein_contrast = 0.25;
  }
  r.perm = make_permutation(mix64(o.seed * 2 + 0x2001));
}

// Once the rock is placed: its albedo gives it tone_ratio times the ground's
// brightness as the left camera sees it (shading included, so a weak boundary
// stays weak under a low sun), then the exposure.
void set_tone_and_exposure(Scene& s) {
  const Eigen::Vector3d cam = camera_centre_world(s.rig.left);
  double shade = 0, weight = 0;
  for (const auto& f : visible_facets(s)) {
    const double lit = std::max(0.0, f.normal.dot(s.sun_dir));
    const double sky = s.ambient * (0.7 + 0.3 * f.normal.z());
    const double w = f.area_mm2 * f.normal.dot((cam - f.centroid).normalized());  // projected area
    shade += w * (lit + sky);
    weight += w;
  }
  const double ground_shade = std::sin(s.sun_elevation_deg * kDeg) + s.ambient;
  const double rock_shade = weight > 0 ? shade / weight : ground_shade;
  TextureRecipe& r = s.rock_surface;
  r.mean_albedo =
      std::clamp(s.ground.mean_albedo * s.tone_ratio * ground_shade / rock_shade, 0.05, 0.9);
  // Sunlit ground near 130 DN unless that would saturate a rock face facing the sun.
  const double lit_ground = s.ground.mean_albedo * ground_shade;
  const double brightest = r.mean_albedo * 1.3 * (1.0 + s.ambient);
  s.gain_dn = std::min(130.0 / lit_ground, 235.0 / brightest);
  s.sky_radiance = 185.0 / s.gain_dn;
}

Eigen::Vector3d sun_direction(double heading_rad, double azimuth_deg, double elevation_deg) {
  const double a = heading_rad + azimuth_deg * kDeg;  // counter-clockwise from the heading
  const double el = elevation_deg * kDeg;
  // Heading h looks along (-sin h, cos h); rotate it counter-clockwise by the azimuth.
  return {-std::sin(a) * std::cos(el), std::cos(a) * std::cos(el), std::sin(el)};
}

bool in_image(const TsaiCamera& cam, const Eigen::Vector3d& p, double margin) {
  auto uv = project(cam, p);
  return uv && uv->x() >= margin && uv->x() <= cam.width - 1 - margin && uv->y() >= margin &&
         uv->y() <= cam.height - 1 - margin;
}

double angle_deg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0)) / kDeg;
}

}  // namespace

bool in_both_views(const Scene& s, const RectifiedPair& pair,
                   const std::vector<Eigen::Vector3d>& pts) {
  for (const auto& p : pts) {
    if (!in_image(s.rig.left, p, kMarginPx) || !in_image(s.rig.right, p, kMarginPx)) return false;
    auto r = rectified_project(pair, p);
    const double m = kMarginPx / 2;
    if (!r || r->uv_left.x() < m || r->uv_left.x() - r->disparity < m ||
        r->uv_left.x() > kImageWidth - 1 - m || r->uv_left.y() < m ||
        r->uv_left.y() > kImageHeight - 1 - m)
      return false;
  }
  return true;
}

const char* rock_kind_name(RockKind kind) {
  switch (kind) {
    case RockKind::grindable:
      return "grindable";
    case RockKind::too_small:
      return "too_small";
    case RockKind::too_rough:
      return "too_rough";
    case RockKind::out_of_reach:
      return "out_of_reach";
  }
  return "?";
}

const FaceRelief& relief_at(const Scene& s, int r) {
  if (r == 0 || s.neighbour_relief.empty()) {
    static const FaceRelief kNone;
    return r == 0 ? s.face_relief : kNone;
  }
  return s.neighbour_relief[static_cast<std::size_t>(r - 1)];
}

namespace {

// Why a placement is refused, in the order the checks run.
constexpr const char* kRefusals[] = {
    "degenerate rock",
    "a flat face was cut away by another",
    "flat faces not visible in both views",
    "flat faces are not the largest facets",
    "a flat face is too small",
    "a flat face is seen too obliquely",
    "two flat faces are nearly parallel",
    "rig cannot be rectified",
    "rock outside an image",
    "shadow outside an image",
    "the sun is below the sloped ground",
    "rig too close to the sloped ground",
    "no touching neighbour leaves the flat faces in view",
    "the further rocks find no place in view",
};

// Why a placement is refused (an entry of kRefusals), or nullptr when it
// meets every requirement.
const char* refusal(const Scene& s) {
  int grind = 0;
  for (const auto& f : s.rock.faces) grind += f.plane.grind_face ? 1 : 0;
  if (grind != s.flat_faces) return kRefusals[1];
  const auto facets = visible_facets(s);
  if (static_cast<int>(facets.size()) < s.flat_faces) return kRefusals[2];
  double largest_rough = 0;
  for (std::size_t i = 0; i < facets.size(); ++i) {
    const bool expect_grind = static_cast<int>(i) < s.flat_faces;
    if (facets[i].grind_face != expect_grind) return kRefusals[3];
    if (!expect_grind) largest_rough = std::max(largest_rough, facets[i].area_mm2);
  }
  const Eigen::Vector3d cl = camera_centre_world(s.rig.left);
  const Eigen::Vector3d cr = camera_centre_world(s.rig.right);
  for (int i = 0; i < s.flat_faces; ++i) {
    const VisibleFacet& f = facets[static_cast<std::size_t>(i)];
    if (f.area_mm2 < kFlatOverRoughArea * largest_rough) return kRefusals[4];
    if (f.area_mm2 < kMinFlatAreaFraction * s.rock_size_mm * s.rock_size_mm) return kRefusals[4];
    if (angle_deg(f.normal, cl - f.centroid) > kMaxViewAngleDeg ||
        angle_deg(f.normal, cr - f.centroid) > kMaxViewAngleDeg)
      return kRefusals[5];
    for (int j = 0; j < i; ++j)
      if (angle_deg(f.normal, facets[static_cast<std::size_t>(j)].normal) < kMinFlatSeparationDeg)
        return kRefusals[6];
  }
  auto pair = rectify_geometry(s.rig, kImageWidth, kImageHeight);
  if (!pair) return kRefusals[7];
  auto in_views = [&](const std::vector<Eigen::Vector3d>& pts) {
    return in_both_views(s, *pair, pts);
  };
  if (!in_views(rock_outline_points(s.rock, 8))) return kRefusals[8];
  if (!in_views(polygon_edge_points(shadow_region(s.rock, s.sun_dir), 8))) return kRefusals[9];
  if (s.tilted && s.sun_dir.z() < std::sin(kMinSunOverSlopeDeg * kDeg)) return kRefusals[10];
  if (s.tilted && 0.5 * (cl + cr).z() < kMinRigOverGroundMm) return kRefusals[11];
  return nullptr;
}

}  // namespace

Result<Scene> make_scene(const SceneOptions& o) {
  PETRA_TRY(validate(o));
  Scene s;
  s.options = o;
  resolve_choices(o, s);
  choose_materials(o, s);
  s.slope_azimuth_deg =
      o.world.slope_azimuth_deg.value_or(Rng(o.seed, kStreamWorld).uniform(-180, 180));
  const double h = s.camera_height_mm;
  const double dist = s.rock_distance_mm;
  Rng geo(o.seed, kStreamGeometry);
  // Refusals come in check order: the latest check ever reached names what
  // kept the options from working.
  const char* furthest = "none";
  auto stage = [](const char* why) {
    for (int i = 0; i < static_cast<int>(std::size(kRefusals)); ++i)
      if (why == kRefusals[i]) return i;
    return -1;
  };
  auto tally = [&](const char* why) {
    if (stage(why) >= stage(furthest)) furthest = why;
  };
  const char* why = nullptr;
  for (int attempt = 1; attempt <= kMaxAttempts; ++attempt) {
    const double phi = geo.uniform(-10, 10) * kDeg;  // rock bearing from the rig
    // Faces are aimed using an estimate of the centre height (exact below).
    const double zc0 = 0.15 * s.rock_size_mm;
    const double horiz0 = std::sqrt(dist * dist - (h - zc0) * (h - zc0));
    RockSpec spec;
    spec.shape = s.shape;
    spec.size_mm = s.rock_size_mm;
    spec.flat_faces = s.flat_faces;
    spec.burial = o.world.burial;
    spec.toward_cameras =
        Eigen::Vector3d(std::sin(phi) * horiz0, -std::cos(phi) * horiz0, h - zc0).normalized();
    auto built = build_rock(geo, spec);
    const double heading_jitter = geo.uniform(-7, 7) * kDeg;
    const double tilt_jitter = geo.uniform(-6, 6) * kDeg;
    const double roll = geo.uniform(-1.5, 1.5) * kDeg;
    if (!built) {
      tally(kRefusals[0]);
      continue;
    }
    const double zc = built->centre_height_mm;
    const double horiz = std::sqrt(dist * dist - (h - zc) * (h - zc));
    s.rock = std::move(built->rock);
    translate_rock(s.rock, Eigen::Vector3d(-std::sin(phi) * horiz, std::cos(phi) * horiz, 0.0));
    s.rock_centre_mm = Eigen::Vector3d(-std::sin(phi) * horiz, std::cos(phi) * horiz, zc);
    RigPose pose;
    pose.midpoint_mm = Eigen::Vector3d(0, 0, h);
    pose.heading_rad = phi + heading_jitter;
    pose.tilt_rad = std::atan2(h - zc, horiz) + tilt_jitter;
    pose.roll_rad = roll;
    s.rig = build_rig(geo, pose);
    s.sun_dir = sun_direction(phi, s.sun_azimuth_deg, s.sun_elevation_deg);
    // A sloped ground: the rig and the sun move into the local ground frame.
    set_slope(s, o.world.slope_deg, phi + s.slope_azimuth_deg * kDeg);
    if (s.tilted) {
      s.rig = rig_to_local(s, s.rig);
      s.sun_dir = s.world_R.transpose() * s.sun_dir;
    }
    s.attempts = attempt;
    why = refusal(s);
    if (!why && o.neighbours > 0 && !add_neighbours(s)) why = kRefusals[12];
    if (!why) set_tone_and_exposure(s);
    if (!why && o.rocks > 1 && !add_rocks(s)) why = kRefusals[13];
    if (!why) {
      add_world_geometry(s);
      set_calibration(s);
      return s;
    }
    tally(why);
  }
  return Error::make(Errc::no_solution, "scene: no placement in %d attempts (furthest: %s)",
                     kMaxAttempts, furthest);
}

}  // namespace petra::sim
