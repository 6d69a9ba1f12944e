#include "sim/scene/scene_rocks.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "algo/arm/arm_trajectory.hpp"
#include "algo/surface/grind_planes.hpp"
#include "sim/scene/face_relief.hpp"

namespace petra::sim {

namespace {

constexpr double kHiddenStepMm = 4;
constexpr double kCentreStepMm = 2;  // disc centres tried on this grid
constexpr double kDiscStepMm = 2;    // surface samples inside a disc
constexpr double kFitStepMm = 2;     // surface samples of a rough facet's fit
constexpr double kReachStepMm = 4;   // disc centres tried for the arm's reach

// In-plane frame of a face: e1, e2 with e1 x e2 = n.
struct PlaneFrame {
  Eigen::Vector3d o, n, e1, e2;
  Eigen::Vector2d to2(const Eigen::Vector3d& p) const { return {e1.dot(p - o), e2.dot(p - o)}; }
  Eigen::Vector3d to3(const Eigen::Vector2d& q) const { return o + q.x() * e1 + q.y() * e2; }
};

PlaneFrame frame_of(const Polygon3& poly, const Eigen::Vector3d& n) {
  PlaneFrame f;
  f.o = polygon_centroid(poly);
  f.n = n;
  f.e1 = n.unitOrthogonal();
  f.e2 = n.cross(f.e1);
  return f;
}

// Smallest distance from q to the polygon's edges, negative outside
// (counter-clockwise in the frame: the inside is left of each edge).
double inner_distance(const std::vector<Eigen::Vector2d>& poly, const Eigen::Vector2d& q) {
  double d = INFINITY;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const Eigen::Vector2d a = poly[i], e = poly[(i + 1) % poly.size()] - a;
    const double len = e.norm();
    if (len < 1e-9) continue;
    d = std::min(d, (e.x() * (q - a).y() - e.y() * (q - a).x()) / len);
  }
  return d;
}

// RMS about its least-squares plane of the surface height -s(x) over the
// disc samples `offsets` (symmetric, so the plane's terms separate).
double disc_rms(const FaceRelief& relief, int face, const HalfSpace& plane, const PlaneFrame& fr,
                const Eigen::Vector2d& centre, const std::vector<Eigen::Vector2d>& offsets) {
  double sum = 0, su = 0, sv = 0, suu = 0, svv = 0;
  std::vector<double> h(offsets.size());
  for (std::size_t i = 0; i < offsets.size(); ++i) {
    h[i] = -face_depth(relief, face, plane, fr.to3(centre + offsets[i]));
    sum += h[i];
    su += offsets[i].x() * h[i];
    sv += offsets[i].y() * h[i];
    suu += offsets[i].x() * offsets[i].x();
    svv += offsets[i].y() * offsets[i].y();
  }
  const double mean = sum / static_cast<double>(h.size()), bu = su / suu, bv = sv / svv;
  double r2 = 0;
  for (std::size_t i = 0; i < offsets.size(); ++i)
    r2 += std::pow(h[i] - mean - bu * offsets[i].x() - bv * offsets[i].y(), 2);
  return std::sqrt(r2 / static_cast<double>(h.size()));
}

std::vector<Eigen::Vector2d> disc_offsets(double radius) {
  std::vector<Eigen::Vector2d> out;
  const int n = static_cast<int>(std::floor(radius / kDiscStepMm));
  for (int i = -n; i <= n; ++i)
    for (int j = -n; j <= n; ++j)
      if (std::hypot(i, j) * kDiscStepMm <= radius)
        out.emplace_back(i * kDiscStepMm, j * kDiscStepMm);
  return out;
}

// RMS of a pure bulge of this curvature over the disc (any position: a
// paraboloid's tilt is the plane's).
double bulge_rms_mm(double curvature_per_mm, double radius) {
  FaceRelief bulge;
  bulge.active = true;
  bulge.curvature_per_mm = curvature_per_mm;
  bulge.bulge_centre.push_back(Eigen::Vector3d::Zero());
  const HalfSpace plane{Eigen::Vector3d::UnitZ(), 0.0, false};
  const Polygon3 unit = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  return disc_rms(bulge, 0, plane, frame_of(unit, plane.normal), {0, 0}, disc_offsets(radius));
}

// A face's exposed polygon in its own plane's frame, with its 2-D extent:
// where disc centres are tried.
struct FacePolygon2 {
  PlaneFrame fr;
  std::vector<Eigen::Vector2d> p2;
  Eigen::Vector2d lo{INFINITY, INFINITY}, hi{-INFINITY, -INFINITY};
};

// False when the exposed polygon is degenerate.
bool face_polygon2(const RockFace& rf, FacePolygon2& out) {
  const Polygon3 poly = exposed_polygon(rf);
  if (poly.size() < 3) return false;
  out.fr = frame_of(poly, rf.plane.normal);
  for (const auto& p : poly) {
    out.p2.push_back(out.fr.to2(p));
    out.lo = out.lo.cwiseMin(out.p2.back());
    out.hi = out.hi.cwiseMax(out.p2.back());
  }
  return true;
}

}  // namespace

double grinder_diameter_mm() {
  return GrindParams{}.grinder_diameter_mm;
}
double max_footprint_rms_mm() {
  return GrindParams{}.max_footprint_rms_mm;
}
double flight_standoff_mm() {
  return arm::ApproachRequest{}.standoff_mm;
}

double flattest_disc_rms_mm(const ConvexRock& rock, const FaceRelief& relief, int face,
                            double diameter_mm, double stop_rms_mm) {
  const RockFace& rf = rock.faces[static_cast<std::size_t>(face)];
  FacePolygon2 g;
  if (!face_polygon2(rf, g)) return -1;
  const double radius = 0.5 * diameter_mm;
  const auto offsets = disc_offsets(radius);
  double best = -1;
  for (double u = g.lo.x(); u <= g.hi.x(); u += kCentreStepMm)
    for (double v = g.lo.y(); v <= g.hi.y(); v += kCentreStepMm) {
      if (inner_distance(g.p2, {u, v}) < radius) continue;
      const double rms =
          relief.active ? disc_rms(relief, face, rf.plane, g.fr, {u, v}, offsets) : 0.0;
      if (best < 0 || rms < best) best = rms;
      if (best <= stop_rms_mm) return best;
    }
  return best;
}

bool facet_hidden(const Scene& s, int r, const VisibleFacet& f, double step_mm) {
  const Eigen::Vector3d cams[2] = {camera_centre_world(s.rig.left),
                                   camera_centre_world(s.rig.right)};
  const Polygon3 poly = exposed_polygon(rock_at(s, r).faces[static_cast<std::size_t>(f.face)]);
  for (const auto& p : polygon_samples(poly, step_mm))
    for (const auto& c : cams)
      for (int o = 0; o < rock_count(s); ++o)
        if (o != r && ray_meets_rock(rock_at(s, o), p, (c - p).normalized(), 1e-6)) return true;
  return false;
}

arm::ArmReason facet_reach(const Scene& s, const Eigen::Vector3d& centroid,
                           const Eigen::Vector3d& normal) {
  arm::ApproachRequest req;
  req.centroid_mm = to_world(s, centroid);
  req.normal = dir_to_world(s, normal).normalized();
  req.standoff_mm = flight_standoff_mm();
  const auto plan = arm::plan_approach(arm::rover_arm_geometry(), arm::default_joint_limits(), req,
                                       arm::stow_pose());
  return plan.refusal.reason;
}

FacetJudgement judge_facet(const Scene& s, int r, const VisibleFacet& f) {
  FacetJudgement j;
  j.reach = facet_reach(s, f.centroid, f.normal);
  j.reachable = j.reach == arm::ArmReason::ok;
  if (facet_hidden(s, r, f, kHiddenStepMm)) return j;  // "hidden"
  const GrindParams flight;
  if (plane_view_angle_deg(f.normal, f.centroid, camera_centre_world(s.rig.left)) >
      flight.max_view_angle_deg) {
    j.reason = "faces_away";
    return j;
  }
  // A disc of the tool's diameter inside the polygon at all (planar test).
  const ConvexRock& rock = rock_at(s, r);
  if (flattest_disc_rms_mm(rock, FaceRelief{}, f.face, flight.grinder_diameter_mm, 0) < 0) {
    j.reason = "too_small";
    return j;
  }
  // Every facet, designed flat face or tangent plane of the rounded body,
  // is rendered as its plane plus the rock's relief (face_relief.hpp): the
  // same measure judges them all.
  const FaceRelief& relief = relief_at(s, r);
  j.disc_rms_mm = flattest_disc_rms_mm(rock, relief, f.face, flight.grinder_diameter_mm,
                                       flight.max_footprint_rms_mm);
  if (j.disc_rms_mm > flight.max_footprint_rms_mm) {
    const double bulge = bulge_rms_mm(relief.curvature_per_mm, 0.5 * flight.grinder_diameter_mm);
    j.reason = bulge > flight.max_footprint_rms_mm ? "too_curved" : "too_rough";
  } else {
    j.grindable = true;
    j.reason = "grindable";
  }
  return j;
}

FacetFit fit_facet(VisibleFacet& f, const std::vector<Eigen::Vector3d>& pts) {
  FacetFit fit;
  if (pts.size() < 20) return fit;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& p : pts) mean += p;
  mean /= static_cast<double>(pts.size());
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const auto& p : pts) cov += (p - mean) * (p - mean).transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
  Eigen::Vector3d n = eig.eigenvectors().col(0);
  if (n.dot(f.normal) < 0) n = -n;
  double sum2 = 0;
  for (const auto& p : pts) sum2 += std::pow(n.dot(p - mean), 2);
  for (auto& p : f.polygon) p -= n * n.dot(p - mean);  // onto the fitted plane
  f.normal = n;
  f.centroid = polygon_centroid(f.polygon);
  f.area_mm2 = polygon_area(f.polygon);
  fit.fitted = true;
  fit.flatness_rms_mm = std::sqrt(sum2 / static_cast<double>(pts.size()));
  fit.points = static_cast<int>(pts.size());
  return fit;
}

std::optional<Eigen::Vector3d> reachable_grindable_disc(const Scene& s, int r,
                                                        const VisibleFacet& f) {
  const RockFace& rf = rock_at(s, r).faces[static_cast<std::size_t>(f.face)];
  FacePolygon2 g;
  if (!face_polygon2(rf, g)) return std::nullopt;
  const double radius = 0.5 * grinder_diameter_mm();
  const auto offsets = disc_offsets(radius);
  const FaceRelief& relief = relief_at(s, r);
  for (double u = g.lo.x(); u <= g.hi.x(); u += kReachStepMm)
    for (double v = g.lo.y(); v <= g.hi.y(); v += kReachStepMm) {
      if (inner_distance(g.p2, {u, v}) < radius) continue;
      const Eigen::Vector3d centre = g.fr.to3({u, v});
      if (facet_reach(s, centre, f.normal) != arm::ArmReason::ok) continue;
      const double rms =
          relief.active ? disc_rms(relief, f.face, rf.plane, g.fr, {u, v}, offsets) : 0.0;
      if (rms <= max_footprint_rms_mm()) return centre;
    }
  return std::nullopt;
}

void judge_rock(const Scene& s, int r, RockTruth& t) {
  t.judged.clear();
  for (const auto& f : t.facets) {
    FacetJudgement j = judge_facet(s, r, f);
    if (j.grindable && !j.reachable) {
      j.reach_disc_centre = reachable_grindable_disc(s, r, f);
      if (j.reach_disc_centre) {
        j.reachable = true;
        j.reach = arm::ArmReason::ok;
      }
    }
    t.judged.push_back(j);
  }
  std::vector<Eigen::Vector3d> pts;
  for (const auto& face : rock_at(s, r).faces)
    for (const auto& p : exposed_polygon(face)) pts.push_back(p);
  t.height_mm = 0;
  t.size_mm = 0;
  for (const auto& p : pts) {
    t.height_mm = std::max(t.height_mm, p.z());
    for (const auto& q : pts) t.size_mm = std::max(t.size_mm, (p - q).head<2>().norm());
  }
}

RockTruth further_rock_truth(const Scene& s, int r) {
  RockTruth t;
  t.facets = visible_facets(s, rock_at(s, r));
  const FaceRelief& relief = relief_at(s, r);
  if (relief.active)
    for (auto& f : t.facets) {
      const HalfSpace& plane = rock_at(s, r).faces[static_cast<std::size_t>(f.face)].plane;
      std::vector<Eigen::Vector3d> surface;
      for (const auto& p : polygon_samples(f.polygon, kFitStepMm))
        surface.push_back(p - plane.normal * face_depth(relief, f.face, plane, p));
      fit_facet(f, surface);
    }
  judge_rock(s, r, t);
  return t;
}

}  // namespace petra::sim
