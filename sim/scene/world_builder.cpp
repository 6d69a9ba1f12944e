#include "sim/scene/world_builder.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <vector>

#include "sim/scene/camera_rays.hpp"
#include "sim/scene/ray_cast.hpp"

namespace petra::sim {

namespace {

constexpr std::uint64_t kStreamStones = 23;
constexpr std::uint64_t kStreamCalib = 24;
constexpr double kStonesOuterMm = 600;  // stones lie within this of the rock's ground point
constexpr int kMaxStones = 300;

TsaiCamera move_camera(const TsaiCamera& c, const Eigen::Matrix3d& r, const Eigen::Vector3d& p) {
  // The camera's frame is unchanged; points are mapped X = r (X' - p) + p.
  TsaiCamera out = c;
  out.R = c.R * r;
  out.T_mm = c.T_mm + c.R * (p - r * p);
  return out;
}

// A small stone: 12 planes tangent to a random ellipsoid of semi-axis a.
Result<ConvexRock> make_stone(Rng& rng, double a) {
  const double b = a * rng.uniform(0.6, 0.9), c = a * rng.uniform(0.4, 0.6);
  const Eigen::Matrix3d q(Eigen::AngleAxisd(rng.uniform(0, 2 * M_PI), Eigen::Vector3d::UnitZ()));
  const Eigen::Matrix3d m = q * Eigen::Vector3d(a * a, b * b, c * c).asDiagonal() * q.transpose();
  std::vector<HalfSpace> planes;
  constexpr int kPlanes = 12;
  for (int k = 0; k < kPlanes; ++k) {
    // Jittered Fibonacci directions.
    const double z = 1.0 - 2.0 * (k + rng.uniform(0.2, 0.8)) / kPlanes;
    const double phi = k * 2.399963 + rng.uniform(-0.3, 0.3);
    const double rr = std::sqrt(std::max(0.0, 1 - z * z));
    const Eigen::Vector3d n(rr * std::cos(phi), rr * std::sin(phi), z);
    planes.push_back({n, std::sqrt(n.dot(m * n)), false});
  }
  return make_convex_rock(planes, Eigen::Vector3d::Zero(), 4 * a);
}

// True when a stone at `centre` (radius r) could hide part of `rock` from a camera.
bool hides(const Scene& s, const ConvexRock& rock, const Eigen::Vector3d& centre, double r) {
  for (const TsaiCamera* cam : {&s.rig.left, &s.rig.right}) {
    const Eigen::Vector3d c = camera_centre_world(*cam);
    const Eigen::Vector3d vr = rock.centre - c, vs = centre - c;
    if (vs.norm() > vr.norm() + rock.radius_mm) continue;
    const double sep = std::acos(std::clamp(vr.normalized().dot(vs.normalized()), -1.0, 1.0));
    const double reach = std::asin(std::min(1.0, rock.radius_mm / vr.norm())) +
                         std::asin(std::min(1.0, r / vs.norm()));
    if (sep < reach) return true;
  }
  return false;
}

// The target, and in a multi-rock scene every further rock too.
bool hides_rock(const Scene& s, const Eigen::Vector3d& centre, double r) {
  const int rocks = s.options.rocks > 1 ? rock_count(s) : 1;
  for (int k = 0; k < rocks; ++k)
    if (hides(s, rock_at(s, k), centre, r)) return true;
  return false;
}

// True when a stone at `centre` (radius r) could touch a neighbouring rock.
bool meets_neighbour(const Scene& s, const Eigen::Vector3d& centre, double r) {
  for (const auto& n : s.neighbours)
    if ((n.centre - centre).norm() < n.radius_mm + r) return true;
  return false;
}

void add_stones(Scene& s) {
  const double density = s.options.world.stones_per_m2;
  if (density <= 0) return;
  Rng rng(s.options.seed, kStreamStones);
  const double r_in = s.rock.radius_mm + 25;
  const double area_m2 = M_PI * (kStonesOuterMm * kStonesOuterMm - r_in * r_in) / 1e6;
  const int count = std::min(kMaxStones, static_cast<int>(std::lround(density * area_m2)));
  for (int k = 0; k < count; ++k) {
    const double a = rng.uniform(5, 20);  // stones 10..40 mm long
    const double r = std::sqrt(rng.uniform(r_in * r_in, kStonesOuterMm * kStonesOuterMm));
    const double th = rng.uniform(0, 2 * M_PI);
    const double sink = rng.uniform(0.0, 0.5);
    const double albedo = rng.uniform(0.7, 1.4);
    auto stone = make_stone(rng, a);
    if (!stone) continue;
    const double x = s.pivot.x() + r * std::cos(th), y = s.pivot.y() + r * std::sin(th);
    double bottom = INFINITY, top = -INFINITY;
    for (const auto& f : stone->faces)
      for (const auto& p : f.polygon) {
        bottom = std::min(bottom, p.z());
        top = std::max(top, p.z());
      }
    // The stone's lowest point lies sink x its height below the local ground.
    const double z = terrain_height(s.terrain, x, y) - sink * (top - bottom) - bottom;
    translate_rock(*stone, Eigen::Vector3d(x, y, z));
    if (hides_rock(s, stone->centre, stone->radius_mm)) continue;
    if (meets_neighbour(s, stone->centre, stone->radius_mm)) continue;
    s.stones.push_back(std::move(*stone));
    s.stone_albedo.push_back(albedo);
  }
}

}  // namespace

void set_slope(Scene& s, double slope_deg, double uphill_azimuth_rad) {
  s.pivot = Eigen::Vector3d(s.rock_centre_mm.x(), s.rock_centre_mm.y(), 0.0);
  if (slope_deg <= 0) return;
  const double sl = slope_deg * M_PI / 180.0;
  const Eigen::Vector3d uphill(-std::sin(uphill_azimuth_rad), std::cos(uphill_azimuth_rad), 0.0);
  const Eigen::Vector3d n_world = -std::sin(sl) * uphill + std::cos(sl) * Eigen::Vector3d::UnitZ();
  s.world_R =
      Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), n_world).toRotationMatrix();
  s.tilted = true;
}

StereoRig rig_to_local(const Scene& s, const StereoRig& world_rig) {
  if (!s.tilted) return world_rig;
  StereoRig out = world_rig;
  out.left = move_camera(world_rig.left, s.world_R, s.pivot);
  out.right = move_camera(world_rig.right, s.world_R, s.pivot);
  return out;
}

StereoRig rig_to_world(const Scene& s, const StereoRig& local_rig) {
  if (!s.tilted) return local_rig;
  StereoRig out = local_rig;
  const Eigen::Matrix3d back = s.world_R.transpose();
  out.left = move_camera(local_rig.left, back, s.pivot);
  out.right = move_camera(local_rig.right, back, s.pivot);
  return out;
}

void add_world_geometry(Scene& s) {
  const World& w = s.options.world;
  s.terrain = make_terrain(w, s.options.seed, s.pivot.head<2>());
  s.face_relief = make_face_relief(w, s.options.seed, s.rock);
  add_stones(s);
}

std::vector<Eigen::Vector3d> visible_world_points(const Scene& s, int step_px) {
  const CameraRays rays(s.rig.left);
  std::vector<Eigen::Vector3d> pts;
  for (int j = step_px / 2; j < s.rig.left.height; j += step_px)
    for (int i = step_px / 2; i < s.rig.left.width; i += step_px) {
      const SceneHit hit = trace(s, rays.origin(), rays.direction(i, j));
      if (hit.surface != kSky) pts.push_back(to_world(s, hit.point));
    }
  return pts;
}

double reprojection_rms_px(const StereoRig& a, const StereoRig& b,
                           const std::vector<Eigen::Vector3d>& pts) {
  double sum = 0;
  long n = 0;
  for (const auto& p : pts)
    for (int k = 0; k < 2; ++k) {
      const TsaiCamera& ca = k == 0 ? a.left : a.right;
      const TsaiCamera& cb = k == 0 ? b.left : b.right;
      auto ua = project(ca, p), ub = project(cb, p);
      if (!ua || !ub || ub->x() < 0 || ub->y() < 0 || ub->x() > cb.width - 1 ||
          ub->y() > cb.height - 1)
        continue;
      sum += (*ua - *ub).squaredNorm();
      ++n;
    }
  return n ? std::sqrt(sum / static_cast<double>(n)) : 0.0;
}

namespace {

// The true rig with error vector e (9 values, each about one pixel per unit) scaled by k.
StereoRig perturbed(const StereoRig& rig, const double e[9], double k) {
  StereoRig out = rig;
  for (int c = 0; c < 2; ++c) {
    TsaiCamera& cam = c == 0 ? out.left : out.right;
    const double px_rad = cam.dy_mm / cam.f_mm;  // one pixel's angle
    const Eigen::Vector3d w(e[3 * c], e[3 * c + 1], e[3 * c + 2]);
    const Eigen::Vector3d centre = camera_centre_world(cam);
    cam.R = Eigen::Matrix3d(Eigen::AngleAxisd(k * px_rad * w.norm(), w.normalized())) * cam.R;
    cam.T_mm = -(cam.R * centre);
  }
  out.right.cx_px += k * e[6];
  out.right.cy_px += k * e[7];
  out.right.f_mm *= 1.0 + k * e[8] * out.right.dy_mm / out.right.f_mm;
  return out;
}

}  // namespace

void set_calibration(Scene& s) {
  s.true_rig_world = rig_to_world(s, s.rig);
  s.calib_rig = s.true_rig_world;
  s.calib_residual_px = 0;
  const double target = s.options.world.calib_residual_px;
  if (target <= 0) return;
  const auto pts = visible_world_points(s, 16);
  Rng rng(s.options.seed, kStreamCalib);
  double e[9];
  for (double& v : e) v = rng.normal();
  double k = 1, rms = 0;
  for (int it = 0; it < 8; ++it) {
    rms = reprojection_rms_px(perturbed(s.true_rig_world, e, k), s.true_rig_world, pts);
    if (rms <= 0) break;
    k *= target / rms;
  }
  s.calib_rig = perturbed(s.true_rig_world, e, k);
  s.calib_residual_px = reprojection_rms_px(s.calib_rig, s.true_rig_world, pts);
}

}  // namespace petra::sim
