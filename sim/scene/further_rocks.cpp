#include "sim/scene/further_rocks.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <optional>
#include <string_view>

#include "sim/scene/camera_rays.hpp"
#include "sim/scene/neighbours.hpp"
#include "sim/scene/rng.hpp"
#include "sim/scene/rock_builder.hpp"
#include "sim/scene/scene_rocks.hpp"

namespace petra::sim {

namespace {

constexpr std::uint64_t kStreamRocks = 26;
constexpr int kTriesPerRock = 80;
constexpr double kTouchShare = 0.3;  // slid against a placed rock until they touch
constexpr double kHiddenStepMm = 6;
constexpr double kSmallSizeMm[2] = {28, 40};  // too small: no grinder disc fits a face
constexpr double kSizeMm[2] = {90, 200};
constexpr double kRoughSizeMm[2] = {80, 130};  // sphere-traced rough faces cost render time
// Too rough: face roughness 2.5..3.5 mm RMS (beyond the option's 2 mm: at 2 mm
// the flattest of a face's discs often stays within the 1 mm tolerance).
constexpr double kRoughMm[2] = {2.5, 3.5};

struct Drawn {
  ConvexRock rock;
  FaceRelief relief;
  double gap_mm = 0;
};

RockKind kind_of(const Scene& s, int r) {
  return static_cast<RockKind>((s.options.seed + static_cast<std::uint64_t>(r)) % kRockKinds);
}

// The ground point (z = 0) the left camera sees at a random pixel, if any.
std::optional<Eigen::Vector3d> ground_point(const Scene& s, Rng& rng) {
  const CameraRays rays(s.rig.left);
  const double u = rng.uniform(0.08, 0.92) * kImageWidth;
  const double v = rng.uniform(0.15, 0.95) * kImageHeight;
  const Eigen::Vector3d d = rays.direction(u, v);
  if (d.z() > -1e-3) return std::nullopt;
  const Eigen::Vector3d g = rays.origin() - d * (rays.origin().z() / d.z());
  return Eigen::Vector3d(g.x(), g.y(), 0.0);
}

// Slides the rock toward a placed one until they touch, then back by a gap.
void touch_a_rock(const Scene& s, Rng& rng, Drawn& d) {
  const ConvexRock& other = rock_at(s, rng.integer(0, rock_count(s) - 1));
  Eigen::Vector3d dir = d.rock.centre - other.centre;
  dir.z() = 0;
  const double reach = dir.norm();
  if (reach < 1) return;
  dir /= reach;
  d.gap_mm = rng.uniform(0.0, kMaxNeighbourGapMm);
  const double slide = contact_slide(other, d.rock, dir, reach);
  if (slide > 0) translate_rock(d.rock, -(slide - d.gap_mm) * dir);
}

Result<Drawn> draw_rock(const Scene& s, Rng& rng, RockKind kind, const FractalStats& noise) {
  const auto g = ground_point(s, rng);
  const bool touch = rng.uniform() < kTouchShare;
  RockSpec spec;
  spec.shape = static_cast<RockShape>(rng.integer(0, 2));
  spec.flat_faces = rng.integer(2, 3);
  const double* size = kind == RockKind::too_small   ? kSmallSizeMm
                       : kind == RockKind::too_rough ? kRoughSizeMm
                                                     : kSizeMm;
  spec.size_mm = rng.uniform(size[0], size[1]);
  spec.burial = s.options.world.burial;  // --burial holds for every rock
  World w = s.options.world;
  const double rough = rng.uniform(kRoughMm[0], kRoughMm[1]);
  if (kind == RockKind::too_rough) w.face_roughness_mm = rough;
  if (!g) return Error::make(Errc::no_solution, "rock: ray misses the ground");
  const Eigen::Vector3d mid =
      0.5 * (camera_centre_world(s.rig.left) + camera_centre_world(s.rig.right));
  spec.toward_cameras = (mid - *g).normalized();
  auto built = build_rock(rng, spec);
  if (!built) return built.error();
  Drawn d;
  d.rock = std::move(built->rock);
  translate_rock(d.rock, *g);
  if (touch) touch_a_rock(s, rng, d);
  d.relief = make_face_relief(w, noise, d.rock);
  return d;
}

// True when the judged facets of rock r are of its kind (stops at the first
// facet that rules it out: judging a rough face searches many discs).
bool of_kind(const Scene& s, int r, RockKind kind) {
  const auto facets = visible_facets(s, rock_at(s, r));
  if (kind == RockKind::out_of_reach)
    for (const auto& f : facets)
      if (facet_reach(s, f.centroid, f.normal) == arm::ArmReason::ok) return false;
  int grindable = 0, small = 0, rough = 0;
  for (const auto& f : facets) {
    if (!f.grind_face && kind == RockKind::out_of_reach) continue;
    const FacetJudgement j = judge_facet(s, r, f);
    const std::string_view why = j.reason;
    if (j.grindable && kind != RockKind::out_of_reach) {
      if (kind != RockKind::grindable) return false;
      if (f.grind_face && j.reachable) return true;
    }
    grindable += j.grindable ? 1 : 0;
    if (!f.grind_face) continue;
    if (kind == RockKind::too_small && why != "too_small") return false;
    small += why == "too_small" ? 1 : 0;
    rough += why == "too_rough" || why == "too_curved" ? 1 : 0;
  }
  switch (kind) {
    case RockKind::grindable:
      return false;  // no grind face grindable and reached
    case RockKind::too_small:
      return small > 0;
    case RockKind::too_rough:
      return rough > 0;
    case RockKind::out_of_reach:
      return grindable > 0;
  }
  return false;
}

// True when some rock's facet is hidden from a camera by another rock.
bool any_facet_hidden(const Scene& s) {
  for (int r = 0; r < rock_count(s); ++r)
    for (const auto& f : visible_facets(s, rock_at(s, r)))
      if (facet_hidden(s, r, f, kHiddenStepMm)) return true;
  return false;
}

void pop_rock(Scene& s) {
  s.neighbours.pop_back();
  s.neighbour_relief.pop_back();
  s.neighbour_kind.pop_back();
  s.neighbour_albedo.pop_back();
  s.neighbour_gap_mm.pop_back();
}

// Adds the drawn rock when it fits the scene and its kind; false otherwise.
bool try_add(Scene& s, Drawn& d, RockKind kind, const RectifiedPair& pair, double albedo) {
  if (!in_both_views(s, pair, rock_outline_points(d.rock, 8))) return false;
  for (int o = 0; o < rock_count(s); ++o)
    if (overlap_above_ground(rock_at(s, o), d.rock)) return false;
  s.neighbours.push_back(std::move(d.rock));
  s.neighbour_relief.push_back(std::move(d.relief));
  s.neighbour_kind.push_back(kind);
  s.neighbour_albedo.push_back(albedo);
  s.neighbour_gap_mm.push_back(d.gap_mm);
  const int r = rock_count(s) - 1;
  const bool fits = !any_facet_hidden(s) && of_kind(s, r, kind);
  if (!fits) pop_rock(s);
  return fits;
}

}  // namespace

Status add_rocks(Scene& s) {
  auto pair = rectify_geometry(s.rig, kImageWidth, kImageHeight);
  if (!pair) return pair.error();
  Rng rng(s.options.seed, kStreamRocks + 16 * static_cast<std::uint64_t>(s.attempts));
  Rng tone(s.options.seed, kStreamRocks);
  const FractalStats noise = fractal_stats(s.options.seed);
  for (int r = 1; r < s.options.rocks; ++r) {
    const RockKind kind = kind_of(s, r);
    const double albedo = tone.uniform(0.85, 1.15);
    bool placed = false;
    for (int t = 0; t < kTriesPerRock && !placed; ++t) {
      auto d = draw_rock(s, rng, kind, noise);
      placed = d && try_add(s, *d, kind, *pair, albedo);
    }
    if (!placed) {
      while (!s.neighbours.empty()) pop_rock(s);
      return Error::make(Errc::no_solution, "rock %d (%s): no place in view", r,
                         rock_kind_name(kind));
    }
  }
  return {};
}

}  // namespace petra::sim
