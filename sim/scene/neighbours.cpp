#include "sim/scene/neighbours.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <vector>

#include "sim/scene/rng.hpp"
#include "sim/scene/rock_builder.hpp"
#include "sim/scene/scene_geometry.hpp"

namespace petra::sim {

namespace {

constexpr double kDeg = M_PI / 180.0;
constexpr std::uint64_t kStreamNeighbours = 25;
constexpr int kTriesPerNeighbour = 40;
constexpr double kMaxBesideDeg = 120;  // 0 = straight behind the rock, 90 = beside it
constexpr double kSampleStepMm = 4;
constexpr double kMinVisibleShare = 0.15;  // of the neighbour's samples facing the left camera

Eigen::Vector3d horizontal(const Eigen::Vector3d& v) {
  return Eigen::Vector3d(v.x(), v.y(), 0.0).normalized();
}

}  // namespace

bool overlap_above_ground(const ConvexRock& a, const ConvexRock& b) {
  std::vector<HalfSpace> planes;
  for (const auto& f : a.faces) planes.push_back(f.plane);
  for (const auto& f : b.faces) planes.push_back(f.plane);
  planes.push_back({-Eigen::Vector3d::UnitZ(), 0.0, false});
  return static_cast<bool>(make_convex_rock(planes, a.centre, a.radius_mm + b.radius_mm));
}

double contact_slide(const ConvexRock& a, const ConvexRock& b, const Eigen::Vector3d& dir,
                     double reach) {
  auto overlaps_at = [&](double s) {
    ConvexRock moved = b;
    translate_rock(moved, -s * dir);
    return overlap_above_ground(a, moved);
  };
  if (overlaps_at(0)) return 0;
  if (!overlaps_at(reach)) return -1;
  double lo = 0, hi = reach;
  while (hi - lo > 0.005) {
    const double mid = 0.5 * (lo + hi);
    (overlaps_at(mid) ? hi : lo) = mid;
  }
  return lo;
}

namespace {

// Share of b's exposed surface facing the left camera that no other rock hides.
double visible_share(const Scene& s, const ConvexRock& b) {
  const Eigen::Vector3d cam = camera_centre_world(s.rig.left);
  int seen = 0, total = 0;
  for (const auto& f : b.faces) {
    if (!faces_point(f, cam)) continue;
    for (const auto& p : polygon_samples(exposed_polygon(f), kSampleStepMm)) {
      ++total;
      const Eigen::Vector3d dir = (cam - p).normalized();
      bool hidden = ray_meets_rock(s.rock, p, dir, 1e-6);
      for (const auto& n : s.neighbours) hidden = hidden || ray_meets_rock(n, p, dir, 1e-6);
      seen += hidden ? 0 : 1;
    }
  }
  return total ? double(seen) / total : 0.0;
}

// One neighbour drawn from rng, slid against the target; fails when it would
// overlap a placed neighbour, hide a grind face, or stay hidden itself.
struct Placed {
  ConvexRock rock;
  double gap_mm = 0;  // slid back this far from the first contact
};

Result<Placed> try_neighbour(const Scene& s, Rng& rng) {
  const Eigen::Vector3d cam = camera_centre_world(s.rig.left);
  const Eigen::Vector3d behind = horizontal(s.rock_centre_mm - cam);
  const double theta = rng.uniform(-kMaxBesideDeg, kMaxBesideDeg) * kDeg;
  const Eigen::Vector3d dir = Eigen::AngleAxisd(theta, Eigen::Vector3d::UnitZ()) * behind;
  RockSpec spec;
  spec.shape = static_cast<RockShape>(rng.integer(0, 2));
  spec.size_mm = s.rock_size_mm * rng.uniform(0.5, 1.0);
  spec.flat_faces = rng.integer(2, 3);
  const double turn = rng.uniform(-60, 60) * kDeg;
  spec.toward_cameras =
      (Eigen::AngleAxisd(turn, Eigen::Vector3d::UnitZ()) * (-behind) + Eigen::Vector3d(0, 0, 0.6))
          .normalized();
  const double gap = rng.uniform(0.0, kMaxNeighbourGapMm);
  auto built = build_rock(rng, spec);
  if (!built) return built.error();
  ConvexRock nb = std::move(built->rock);
  const double start = s.rock.radius_mm + nb.radius_mm + 5;
  const Eigen::Vector3d base(s.rock_centre_mm.x(), s.rock_centre_mm.y(), 0.0);
  translate_rock(nb, base + start * dir);
  const double slide = contact_slide(s.rock, nb, dir, start);
  if (slide <= 0) return Error::make(Errc::no_solution, "neighbour: no contact");
  translate_rock(nb, -(slide - gap) * dir);
  for (const auto& other : s.neighbours)
    if (overlap_above_ground(other, nb))
      return Error::make(Errc::no_solution, "neighbour: overlaps another");
  if (hides_grind_face(s, nb, kSampleStepMm))
    return Error::make(Errc::no_solution, "neighbour: hides a grind face");
  if (visible_share(s, nb) < kMinVisibleShare)
    return Error::make(Errc::no_solution, "neighbour: hidden behind the rock");
  return Placed{std::move(nb), gap};
}

}  // namespace

bool hides_grind_face(const Scene& s, const ConvexRock& other, double step_mm) {
  const Eigen::Vector3d cams[2] = {camera_centre_world(s.rig.left),
                                   camera_centre_world(s.rig.right)};
  for (const auto& f : visible_facets(s)) {
    if (!f.grind_face) continue;
    for (const auto& p : polygon_samples(f.polygon, step_mm))
      for (const auto& c : cams)
        if (ray_meets_rock(other, p, (c - p).normalized(), 1e-6)) return true;
  }
  return false;
}

Status add_neighbours(Scene& s) {
  Rng rng(s.options.seed, kStreamNeighbours + 16 * static_cast<std::uint64_t>(s.attempts));
  Rng tone(s.options.seed, kStreamNeighbours);
  for (int k = 0; k < s.options.neighbours; ++k) {
    bool placed = false;
    for (int t = 0; t < kTriesPerNeighbour && !placed; ++t) {
      auto nb = try_neighbour(s, rng);
      if (!nb) continue;
      s.neighbour_gap_mm.push_back(nb->gap_mm);
      s.neighbours.push_back(std::move(nb->rock));
      s.neighbour_albedo.push_back(tone.uniform(0.85, 1.15));
      placed = true;
    }
    if (!placed) {
      s.neighbours.clear();
      s.neighbour_albedo.clear();
      s.neighbour_gap_mm.clear();
      return Error::make(Errc::no_solution, "no touching neighbour leaves the flat faces in view");
    }
  }
  return {};
}

}  // namespace petra::sim
