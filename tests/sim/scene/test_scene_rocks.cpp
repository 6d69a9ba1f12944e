// Multi-rock scenes (docs/scene.md "Several rocks"), checked without
// rendering the images: the rocks do not overlap, every truth facet of every
// rock is seen by both cameras (the renderer's own rays, stones and relief
// included), the set holds every kind of rock, and each truth flag agrees
// with a check of its own: the arm's plan_approach for reach, the polygon's
// inscribed circle (fine grid) for a face too small, discs sampled by the
// test for a face too rough, and for a grindable facet (a designed flat face
// or a tangent plane of the rounded body alike) a flat disc of the surface
// the renderer draws (its own rays).
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <set>
#include <string>

#include "algo/arm/arm_trajectory.hpp"
#include "sim/scene/disparity_truth.hpp"
#include "sim/scene/face_relief.hpp"
#include "sim/scene/ray_cast.hpp"
#include "sim/scene/scene_geometry.hpp"
#include "sim/scene/scene_rocks.hpp"
#include "sim/scene/scene_set.hpp"
#include "tests/sim/scene/independent_scene_check.hpp"

namespace petra::sim {
namespace {

// Radius of the largest circle inside a planar convex polygon, on a 0.25 mm
// grid; stops once it exceeds `enough`.
double inscribed_radius(const Polygon3& poly, const Eigen::Vector3d& n, double enough) {
  const Eigen::Vector3d e1 = n.unitOrthogonal(), e2 = n.cross(e1), o = poly[0];
  std::vector<double> x, y;
  for (const auto& p : poly) x.push_back(e1.dot(p - o)), y.push_back(e2.dot(p - o));
  const auto [x0, x1] = std::minmax_element(x.begin(), x.end());
  const auto [y0, y1] = std::minmax_element(y.begin(), y.end());
  double best = 0;
  for (double u = *x0; u <= *x1; u += 0.25)
    for (double v = *y0; v <= *y1; v += 0.25) {
      double d = INFINITY;
      for (std::size_t i = 0; i < x.size() && d > best; ++i) {
        const std::size_t j = (i + 1) % x.size();
        const double ex = x[j] - x[i], ey = y[j] - y[i], len = std::hypot(ex, ey);
        if (len > 1e-9) d = std::min(d, (ex * (v - y[i]) - ey * (u - x[i])) / len);
      }
      best = std::max(best, d);
      if (best > enough) return best;
    }
  return best;
}

// RMS of points about their own least-squares plane (the test's own fit).
double rms_about_own_plane(const std::vector<Eigen::Vector3d>& pts) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& p : pts) mean += p;
  mean /= static_cast<double>(pts.size());
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const auto& p : pts) cov += (p - mean) * (p - mean).transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
  return std::sqrt(std::max(0.0, eig.eigenvalues()(0)) / static_cast<double>(pts.size()));
}

// RMS about its own least-squares plane of the rough surface over a disc of
// radius r at c (samples every 1 mm; the test's own fit).
double disc_rms(const FaceRelief& relief, int face, const HalfSpace& plane,
                const Eigen::Vector3d& c, double r) {
  const Eigen::Vector3d e1 = plane.normal.unitOrthogonal(), e2 = plane.normal.cross(e1);
  std::vector<Eigen::Vector3d> pts;
  for (double u = -r; u <= r; u += 1)
    for (double v = -r; v <= r; v += 1)
      if (u * u + v * v <= r * r) {
        const Eigen::Vector3d x = c + u * e1 + v * e2;
        pts.push_back(x - plane.normal * face_depth(relief, face, plane, x));
      }
  return rms_about_own_plane(pts);
}

// RMS about its least-squares plane of the points the renderer's rays
// (trace(), along -n from 2 mm out) meet on rock r over a disc of radius
// `radius` at c, samples every 2 mm; INFINITY when a ray meets anything else.
double rendered_disc_rms(const Scene& s, int r, const HalfSpace& plane, const Eigen::Vector3d& c,
                         double radius) {
  const Eigen::Vector3d e1 = plane.normal.unitOrthogonal(), e2 = plane.normal.cross(e1);
  std::vector<Eigen::Vector3d> pts;
  for (double u = -radius; u <= radius; u += 2)
    for (double v = -radius; v <= radius; v += 2) {
      if (u * u + v * v > radius * radius) continue;
      const SceneHit hit = trace(s, c + u * e1 + v * e2 + 2 * plane.normal, -plane.normal);
      if (face_of_rock(hit.surface, r) < 0) return INFINITY;
      pts.push_back(hit.point);
    }
  return rms_about_own_plane(pts);
}

// The flattest rendered disc of the grinder's size inside the exposed
// polygon of rock r's face (centres every 3 mm at least a radius inside the
// edges), stopping at the first within `enough`; INFINITY when none fits.
double flattest_rendered_disc(const Scene& s, int r, int face, double enough) {
  const RockFace& rf = rock_at(s, r).faces[static_cast<std::size_t>(face)];
  const Polygon3 poly = exposed_polygon(rf);
  const Eigen::Vector3d n = rf.plane.normal;
  const double radius = 0.5 * grinder_diameter_mm();
  double best = INFINITY;
  for (const auto& c : polygon_samples(poly, 3)) {
    bool inside = true;
    for (std::size_t i = 0; i < poly.size() && inside; ++i) {
      const Eigen::Vector3d a = poly[i], e = poly[(i + 1) % poly.size()] - a;
      if (e.norm() > 1e-9) inside = n.cross(e.normalized()).dot(c - a) >= radius;
    }
    if (!inside) continue;
    best = std::min(best, rendered_disc_rms(s, r, rf.plane, c, radius));
    if (best <= enough) break;
  }
  return best;
}

bool plan_ok(const Scene& s, const Eigen::Vector3d& point, const Eigen::Vector3d& normal) {
  arm::ApproachRequest req;
  req.centroid_mm = to_world(s, point);
  req.normal = dir_to_world(s, normal);
  req.standoff_mm = 50;  // the flight default (ArmGoal, fsw/arm/arm_service.hpp)
  return arm::plan_approach(arm::rover_arm_geometry(), arm::default_joint_limits(), req,
                            arm::stow_pose())
      .ok();
}

// Every rock's facets as truth.json lists them (rock 0 unfitted: no render).
std::vector<RockTruth> truths(const Scene& s) {
  std::vector<RockTruth> out;
  RockTruth first;
  first.facets = visible_facets(s);
  judge_rock(s, 0, first);
  out.push_back(first);
  for (int r = 1; r < rock_count(s); ++r) out.push_back(further_rock_truth(s, r));
  return out;
}

// Entries 0 and 1 of the set hold further rocks of all four kinds; built
// and judged once for the tests below.
struct SetScene {
  Scene scene;
  std::vector<RockTruth> rocks;
};
const SetScene& set_scene(int k) {
  static std::vector<SetScene> scenes = [] {
    std::vector<SetScene> v;
    for (int e = 0; e < 2; ++e) {
      auto s = make_scene(multi_rock_scene_set()[static_cast<std::size_t>(e)]);
      EXPECT_TRUE(s) << s.error().message;
      SetScene x{s ? std::move(*s) : Scene{}, {}};
      if (s) x.rocks = truths(x.scene);
      v.push_back(std::move(x));
    }
    return v;
  }();
  return scenes[static_cast<std::size_t>(k)];
}

TEST(SceneRocks, CountIsValidatedByName) {
  SceneOptions o;
  o.rocks = 7;
  Status st = validate(o);
  ASSERT_FALSE(st.ok());
  EXPECT_EQ(std::string(st.error().message).rfind("rocks = 7", 0), 0u) << st.error().message;
  o.rocks = 0;
  EXPECT_FALSE(validate(o).ok());
  o.rocks = 3;
  EXPECT_TRUE(validate(o).ok());
  o.neighbours = 1;
  EXPECT_FALSE(validate(o).ok());
}

// Seed 5 with two rocks, the clean world.
SceneOptions two_clean_rocks() {
  SceneOptions o;
  o.seed = 5;
  o.rocks = 2;
  return o;
}

TEST(SceneRocks, TwoRocksInTheCleanWorld) {
  SceneOptions o = two_clean_rocks();
  auto s = make_scene(o);
  ASSERT_TRUE(s) << s.error().message;
  ASSERT_EQ(rock_count(*s), 2);
  EXPECT_EQ(s->neighbour_kind[0], static_cast<RockKind>((o.seed + 1) % kRockKinds));
  // Rock 0 is the one rock of the same seed (its placement took the further rock).
  o.rocks = 1;
  auto one = make_scene(o);
  ASSERT_TRUE(one);
  ASSERT_EQ(s->attempts, one->attempts);
  EXPECT_EQ(s->rock_centre_mm, one->rock_centre_mm);
  EXPECT_EQ(s->rock.faces.size(), one->rock.faces.size());
}

TEST(SceneRocks, TheSetHoldsEveryKindByDesign) {
  const auto set = multi_rock_scene_set();
  ASSERT_EQ(set.size(), static_cast<std::size_t>(kMultiSetSize));
  std::set<std::uint64_t> kinds;
  for (const auto& o : set) {
    EXPECT_GE(o.rocks, 3);
    EXPECT_LE(o.rocks, kMaxRocks);
    EXPECT_FALSE(is_clean(o.world));
    for (int r = 1; r < o.rocks; ++r) kinds.insert((o.seed + r) % kRockKinds);
  }
  EXPECT_EQ(kinds.size(), static_cast<std::size_t>(kRockKinds));
}

TEST(SceneRocks, RocksDoNotOverlapAndAreOfTheirKinds) {
  std::set<RockKind> seen;
  for (int k = 0; k < 2; ++k) {
    const Scene& s = set_scene(k).scene;
    ASSERT_EQ(rock_count(s), multi_rock_scene_set()[static_cast<std::size_t>(k)].rocks);
    ASSERT_EQ(s.neighbour_kind.size(), s.neighbours.size());
    for (int a = 0; a < rock_count(s); ++a)
      for (int b = 0; b < rock_count(s); ++b) {
        if (a == b) continue;
        double deepest = 0;
        for (const auto& p : check::exposed_edge_points(rock_at(s, a)))
          deepest = std::max(deepest, check::depth_inside(rock_at(s, b), p));
        EXPECT_LT(deepest, 0.01) << "entry " << k << ": rock " << a << " inside rock " << b;
      }
    for (const RockKind kind : s.neighbour_kind) seen.insert(kind);
  }
  EXPECT_EQ(seen.size(), static_cast<std::size_t>(kRockKinds));
}

TEST(SceneRocks, EveryTruthFacetIsSeenByBothCameras) {
  for (int k = 0; k < 2; ++k) {
    const Scene& s = set_scene(k).scene;
    const auto& rocks = set_scene(k).rocks;
    for (std::size_t r = 0; r < rocks.size(); ++r)
      for (const auto& f : rocks[r].facets) {
        const Polygon3 poly = exposed_polygon(rock_at(s, static_cast<int>(r)).faces[f.face]);
        int hidden = 0, total = 0;
        for (const auto& p : polygon_samples(poly, 5)) {
          if (p.z() < 6) continue;  // the relief may cover a facet's foot
          for (const TsaiCamera* cam : {&s.rig.left, &s.rig.right}) {
            ++total;
            auto uv = project(*cam, p);
            const bool in =
                uv && uv->x() >= 0 && uv->y() >= 0 && uv->x() < cam->width && uv->y() < cam->height;
            hidden += in && visible_from(s, camera_centre_world(*cam), p) ? 0 : 1;
          }
        }
        EXPECT_EQ(hidden, 0) << "entry " << k << " rock " << r << " face " << f.face << ": "
                             << hidden << " of " << total << " samples unseen";
      }
  }
}

TEST(SceneRocks, TruthFlagsAgreeWithIndependentChecks) {
  const double radius = 0.5 * grinder_diameter_mm();
  int small = 0, rough = 0, unreachable = 0, grindable = 0, tangent = 0, at_disc = 0;
  for (int k = 0; k < 2; ++k) {
    const Scene& s = set_scene(k).scene;
    const auto& rocks = set_scene(k).rocks;
    for (std::size_t r = 0; r < rocks.size(); ++r)
      for (std::size_t i = 0; i < rocks[r].facets.size(); ++i) {
        const VisibleFacet& f = rocks[r].facets[i];
        const FacetJudgement& j = rocks[r].judged[i];
        const std::string why = j.reason;
        const ConvexRock& rock = rock_at(s, static_cast<int>(r));
        const RockFace& face = rock.faces[static_cast<std::size_t>(f.face)];
        if (j.reach_disc_centre) {
          // Out of reach at the centroid, reached at a disc the renderer
          // draws within the tolerance (the test's slack as below).
          ++at_disc;
          EXPECT_FALSE(plan_ok(s, f.centroid, f.normal)) << "entry " << k << " rock " << r;
          EXPECT_TRUE(j.grindable && j.reachable) << "entry " << k << " rock " << r;
          EXPECT_TRUE(plan_ok(s, *j.reach_disc_centre, f.normal)) << "entry " << k << " rock " << r;
          EXPECT_LE(
              rendered_disc_rms(s, static_cast<int>(r), face.plane, *j.reach_disc_centre, radius),
              1.1 * max_footprint_rms_mm())
              << "entry " << k << " rock " << r;
        } else {
          EXPECT_EQ(j.reachable, plan_ok(s, f.centroid, f.normal))
              << "entry " << k << " rock " << r;
        }
        unreachable += j.reachable ? 0 : 1;
        const double inradius =
            inscribed_radius(exposed_polygon(face), face.plane.normal, radius + 1.5);
        if (why == "too_small") {
          EXPECT_LT(inradius, radius + 1.5) << "entry " << k << " rock " << r;  // 2 mm centre grid
          small += f.grind_face ? 1 : 0;
        }
        if (why != "too_small" && why != "hidden" && why != "faces_away") {
          EXPECT_GE(inradius, radius) << "entry " << k << " rock " << r;
        }
        if (j.grindable) {
          // The renderer draws a disc this flat there, on a designed flat
          // face or on a tangent plane of the rounded body alike (a little
          // slack: the test samples every 2 mm on its own grid).
          EXPECT_LE(
              flattest_rendered_disc(s, static_cast<int>(r), f.face, 1.1 * max_footprint_rms_mm()),
              1.1 * max_footprint_rms_mm())
              << "entry " << k << " rock " << r << " face " << f.face;
          tangent += f.grind_face ? 0 : 1;
        }
        if (why == "too_rough") {
          ++rough;
          // Any disc inside the face is rougher than the tolerance (a little
          // slack: the test samples every 1 mm, the truth every 2 mm).
          const FaceRelief& relief = relief_at(s, static_cast<int>(r));
          EXPECT_GT(
              disc_rms(relief, f.face, face.plane, polygon_centroid(exposed_polygon(face)), radius),
              0.9 * max_footprint_rms_mm());
        }
        grindable += j.grindable && j.reachable ? 1 : 0;
      }
  }
  EXPECT_GT(small, 0);
  EXPECT_GT(rough, 0);
  EXPECT_GT(unreachable, 0);
  EXPECT_GT(grindable, 0);
  EXPECT_GT(tangent, 0);  // rendered flat: judged as the designed faces are
  std::printf("facets reached at a grindable disc, not at their centroid: %d\n", at_disc);
}

// The same rock's facets, flat (clean world) and then under a bulge of 100/m
// (the relief's curvature alone, no roughness; far beyond --face-curvature's
// 5/m, the only way to bulge 1 mm RMS over the grinder's disc): every facet
// that holds a disc and faces the camera is grindable when flat, the tangent
// planes of the rounded body included (the renderer's rays find the disc
// flat), and too_curved under the bulge, the test's own 1 mm samples of the
// face's relief finding its crown's disc beyond the tolerance. (At such a
// bulge the renderer's neighbouring caps carve the faces: the truth's
// per-face relief is exact only for the realistic bulges, docs/scene.md.)
TEST(SceneRocks, TangentFacetsAreJudgedByTheirRenderedSurface) {
  const SceneOptions o = two_clean_rocks();
  auto flat = make_scene(o);
  ASSERT_TRUE(flat) << flat.error().message;
  Scene curved = *flat;
  World bulge;
  bulge.face_curvature_per_m = 100;
  curved.face_relief = make_face_relief(bulge, o.seed, curved.rock);
  int tangent = 0, judged = 0;
  for (const auto& f : visible_facets(*flat)) {
    const FacetJudgement j = judge_facet(*flat, 0, f);
    const std::string why = j.reason;
    if (why == "hidden" || why == "faces_away" || why == "too_small") continue;
    ++judged;
    EXPECT_TRUE(j.grindable) << "face " << f.face << ": " << why;
    EXPECT_LE(flattest_rendered_disc(*flat, 0, f.face, 0.05), 0.05) << "face " << f.face;
    tangent += f.grind_face ? 0 : 1;
    const FacetJudgement c = judge_facet(curved, 0, f);
    EXPECT_STREQ(c.reason, "too_curved") << "face " << f.face;
    const HalfSpace& plane = curved.rock.faces[static_cast<std::size_t>(f.face)].plane;
    const Eigen::Vector3d crown = curved.face_relief.bulge_centre[static_cast<std::size_t>(f.face)];
    EXPECT_GT(disc_rms(curved.face_relief, f.face, plane, crown, 0.5 * grinder_diameter_mm()),
              max_footprint_rms_mm())
        << "face " << f.face;
  }
  EXPECT_GT(judged, 0);
  EXPECT_GT(tangent, 0);
}

}  // namespace
}  // namespace petra::sim

namespace petra::sim {
namespace {

// The whole set's composition, without rendering (docs/scene.md "Several
// rocks"): run with --gtest_also_run_disabled_tests.
TEST(SceneRocks, DISABLED_SetComposition) {
  int kinds[kRockKinds] = {}, targets = 0, facets = 0, target_rocks = 0;
  for (const auto& o : multi_rock_scene_set()) {
    auto s = make_scene(o);
    ASSERT_TRUE(s) << s.error().message;
    for (const RockKind k : s->neighbour_kind) ++kinds[static_cast<int>(k)];
    int here = 0;
    for (const auto& rock : truths(*s)) {
      int on_rock = 0;
      for (const auto& j : rock.judged) on_rock += j.grindable && j.reachable ? 1 : 0;
      facets += static_cast<int>(rock.facets.size());
      here += on_rock;
      target_rocks += on_rock > 0 ? 1 : 0;
    }
    targets += here;
    std::printf("seed %llu: %d rocks, %d grindable and reachable facets\n",
                static_cast<unsigned long long>(o.seed), rock_count(*s), here);
  }
  std::printf("further rocks: %d grindable, %d too small, %d too rough, %d out of reach\n",
              kinds[0], kinds[1], kinds[2], kinds[3]);
  std::printf("targets: %d grindable and reachable facets on %d rocks; %d facets in all\n", targets,
              target_rocks, facets);
}

}  // namespace
}  // namespace petra::sim
