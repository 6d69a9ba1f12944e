// The renderer is geometrically exact: rock edges appear where the camera
// model projects them (sub-pixel), the disparity truth triangulates back onto
// the scene, and the shadow truth matches independent shadow rays.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "algo/camera/rectify_geometry.hpp"
#include "independent_scene_check.hpp"
#include "sim/scene/disparity_truth.hpp"
#include "sim/scene/render_view.hpp"
#include "sim/scene/scene_geometry.hpp"
#include "sim/scene/scene_set.hpp"
#include "sim/scene/scene_truth.hpp"

namespace petra::sim {
namespace {

double bilinear(const io::GrayImage& img, double x, double y) {
  const int x0 = static_cast<int>(std::floor(x)), y0 = static_cast<int>(std::floor(y));
  const double fx = x - x0, fy = y - y0;
  auto at = [&](int i, int j) { return static_cast<double>(img.view()(i, j)); };
  return (1 - fy) * ((1 - fx) * at(x0, y0) + fx * at(x0 + 1, y0)) +
         fy * ((1 - fx) * at(x0, y0 + 1) + fx * at(x0 + 1, y0 + 1));
}

// Pixels around the rock and its shadow in one camera, plus a margin.
Rect rock_window(const Scene& s, const TsaiCamera& cam, int margin) {
  auto pts = rock_outline_points(s.rock, 8);
  const auto sh = polygon_edge_points(shadow_region(s.rock, s.sun_dir), 8);
  pts.insert(pts.end(), sh.begin(), sh.end());
  double u0 = 1e9, v0 = 1e9, u1 = -1e9, v1 = -1e9;
  for (const auto& p : pts) {
    auto uv = project(cam, p);
    if (!uv) continue;
    u0 = std::min(u0, uv->x());
    v0 = std::min(v0, uv->y());
    u1 = std::max(u1, uv->x());
    v1 = std::max(v1, uv->y());
  }
  const int x0 = std::max(0, static_cast<int>(u0) - margin),
            y0 = std::max(0, static_cast<int>(v0) - margin);
  const int x1 = std::min(cam.width, static_cast<int>(u1) + margin),
            y1 = std::min(cam.height, static_cast<int>(v1) + margin);
  return {x0, y0, x1 - x0, y1 - y0};
}

// What an image point sees: 2 x (rock face index, or -1 for the ground),
// plus 1 when in shadow.
int surface_at(const check::IndependentCaster& caster, const TsaiCamera& cam,
               const Eigen::Vector2d& uv) {
  const Ray ray = pixel_to_ray(cam, uv);
  const check::Hit h = caster.first_hit(ray.origin_mm, ray.direction);
  return 2 * (h.rock ? h.face : -1) + (caster.shadowed(h) ? 1 : 0);
}

struct EdgeStats {
  int measured = 0;
  double mean_abs_px = 0;
  double max_abs_px = 0;
};

// Finds, across each projected rock edge, where the rendered intensity steps
// (the integral of the normalised profile locates a blurred step exactly)
// and compares it with the edge's projection by algo's project().
EdgeStats measure_edges(const Scene& s, const TsaiCamera& cam, const io::GrayImage& img) {
  constexpr double kHalf = 4.0, kStep = 0.05;
  const Eigen::Vector3d centre = camera_centre_world(cam);
  const check::IndependentCaster caster(s);
  EdgeStats st;
  double sum = 0;
  for (std::size_t fi = 0; fi < s.rock.faces.size(); ++fi) {
    const RockFace& face = s.rock.faces[fi];
    if (!faces_point(face, centre)) continue;
    const Polygon3 poly = exposed_polygon(face);
    if (poly.size() < 3) continue;
    const Eigen::Vector3d mid = polygon_centroid(poly);
    for (std::size_t e = 0; e < poly.size(); ++e) {
      const Eigen::Vector3d a = poly[e], b = poly[(e + 1) % poly.size()];
      auto ua = project(cam, a), ub = project(cam, b);
      if (!ua || !ub || (*ua - *ub).norm() < 16) continue;  // long edges only
      for (double f : {0.3, 0.4, 0.5, 0.6, 0.7}) {
        const Eigen::Vector3d p = a + f * (b - a);
        auto up = project(cam, p);
        auto ut = project(cam, p + 0.01 * (b - a));
        // Towards the face: a point just inside it, seen by the camera.
        auto ui = project(cam, p + 0.01 * (mid - p));
        EXPECT_TRUE(up && ut && ui);
        if (!up || !ut || !ui) continue;
        const Eigen::Vector2d tangent = (*ut - *up).normalized();
        Eigen::Vector2d n(-tangent.y(), tangent.x());
        if (n.dot(*ui - *up) < 0) n = -n;
        const Eigen::Vector2d lo = *up - (kHalf + 1) * n, hi = *up + (kHalf + 1) * n;
        if (std::min({lo.x(), hi.x(), lo.y(), hi.y()}) < 1 ||
            std::max(lo.x(), hi.x()) > img.width - 2 || std::max(lo.y(), hi.y()) > img.height - 2)
          continue;
        // One surface on each side across the whole profile: no thin facet
        // seen at a grazing angle hugging the edge.
        // Shadow edges on the ground count as edges too: a thin cast-shadow
        // wedge along the rock's foot (sun grazing the face) is checked for
        // with fine steps next to the edge.
        const int in_surface = surface_at(caster, cam, *up + 0.02 * n);
        const int out_surface = surface_at(caster, cam, *up - 0.02 * n);
        bool clean = in_surface / 2 == static_cast<int>(fi) && out_surface / 2 != in_surface / 2;
        for (double t = 0.02; t <= kHalf + 0.5 && clean; t += t < 0.5 ? 0.02 : 0.25)
          clean = surface_at(caster, cam, *up + t * n) == in_surface &&
                  surface_at(caster, cam, *up - t * n) == out_surface;
        if (!clean) continue;
        std::vector<double> prof;
        for (double t = -kHalf; t <= kHalf + 1e-9; t += kStep) {
          const Eigen::Vector2d q = *up + t * n;
          prof.push_back(bilinear(img, q.x(), q.y()));
        }
        // Plateaus 2.5..4 px either side must be flat (no other edge nearby)
        // and differ enough to locate the step.
        const std::size_t k_in = static_cast<std::size_t>((kHalf + 2.5) / kStep);
        const std::size_t k_out = static_cast<std::size_t>((kHalf - 2.5) / kStep);
        const auto in = std::minmax_element(prof.begin() + static_cast<long>(k_in), prof.end());
        const auto out =
            std::minmax_element(prof.begin(), prof.begin() + static_cast<long>(k_out) + 1);
        if (*in.second - *in.first > 1.0 || *out.second - *out.first > 1.0) continue;
        const double inside = 0.5 * (*in.first + *in.second);
        const double outside = 0.5 * (*out.first + *out.second);
        if (std::abs(inside - outside) < 12) continue;
        double area = 0;  // integral of the profile normalised 0 (outside) .. 1 (inside)
        for (std::size_t k = 0; k + 1 < prof.size(); ++k)
          area +=
              0.5 * kStep * ((prof[k] - outside) + (prof[k + 1] - outside)) / (inside - outside);
        const double step_at = kHalf - area;  // where a sharp step with this integral would be
        ++st.measured;
        sum += std::abs(step_at);
        st.max_abs_px = std::max(st.max_abs_px, std::abs(step_at));
      }
    }
  }
  st.mean_abs_px = st.measured ? sum / st.measured : 0;
  return st;
}

SceneOptions flat_shaded(int set_index) {
  SceneOptions o = standard_scene_set()[static_cast<std::size_t>(set_index)];
  o.texture = false;  // plain faces: their edges are clean intensity steps
  o.noise_sigma_dn = 0;
  return o;
}

TEST(RenderGeometry, RockEdgesLandWhereTheCameraModelProjectsThem) {
  for (int k : {2, 7}) {
    auto s = make_scene(flat_shaded(k));
    ASSERT_TRUE(s.ok()) << s.error().message;
    for (Eye eye : {Eye::left, Eye::right}) {
      const TsaiCamera& cam = eye == Eye::left ? s->rig.left : s->rig.right;
      const RenderedView v = render_view(*s, eye, rock_window(*s, cam, 12));
      const EdgeStats st = measure_edges(*s, cam, v.image);
      std::printf("scene %d %s: %d edge points, mean |offset| %.3f px, max %.3f px\n", k,
                  eye == Eye::left ? "left" : "right", st.measured, st.mean_abs_px, st.max_abs_px);
      EXPECT_GE(st.measured, 20);
      EXPECT_LT(st.mean_abs_px, 0.05);
      EXPECT_LT(st.max_abs_px, 0.15);
    }
  }
}

// Strong barrel distortion moves the rock's edges by pixels: the renderer
// must still put them where project() does.
TEST(RenderGeometry, EdgesStayExactUnderStrongDistortion) {
  auto s = make_scene(flat_shaded(2));
  ASSERT_TRUE(s.ok()) << s.error().message;
  s->rig.left.kappa1 = 0.02;
  // Turn the camera (about its centre) so the rock is seen far from the principal point.
  const Eigen::Vector3d c = camera_centre_world(s->rig.left);
  s->rig.left.R = Eigen::Matrix3d(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitY())) * s->rig.left.R;
  s->rig.left.T_mm = -(s->rig.left.R * c);
  ASSERT_TRUE(validate(s->rig.left).ok());
  // How far distortion moves the rock's centre: a model without it would miss by this much.
  auto with = project(s->rig.left, s->rock.centre);
  TsaiCamera pinhole = s->rig.left;
  pinhole.kappa1 = 0;
  auto without = project(pinhole, s->rock.centre);
  ASSERT_TRUE(with && without);
  const double shift = (*with - *without).norm();
  const RenderedView v = render_view(*s, Eye::left, rock_window(*s, s->rig.left, 12));
  const EdgeStats st = measure_edges(*s, s->rig.left, v.image);
  std::printf(
      "distortion shifts the rock by %.1f px; %d edge points, mean |offset| %.3f px, max %.3f px\n",
      shift, st.measured, st.mean_abs_px, st.max_abs_px);
  EXPECT_GT(shift, 5.0);
  EXPECT_GE(st.measured, 20);
  EXPECT_LT(st.mean_abs_px, 0.05);
  EXPECT_LT(st.max_abs_px, 0.15);
}

TEST(RenderGeometry, DisparityTruthTriangulatesOntoTheScene) {
  auto s = make_scene(standard_scene_set()[3]);
  ASSERT_TRUE(s.ok()) << s.error().message;
  auto rt = render_rectified_truth(*s);
  ASSERT_TRUE(rt.ok()) << rt.error().message;
  const RectifiedPair& pair = rt->pair;
  const check::IndependentCaster caster(*s);
  const Eigen::Vector3d cl = camera_centre_world(s->rig.left);
  const Eigen::Vector3d cr = camera_centre_world(s->rig.right);
  const SceneTruth truth = compute_truth(*s, *rt);
  const Rect r = truth.roi_rectified;
  int valid = 0, invalid = 0, bad_valid = 0, bad_invalid = 0;
  double worst_px = 0;
  for (int y = r.y; y < r.y + r.h; y += 2)
    for (int x = r.x; x < r.x + r.w; x += 2) {
      const double d = rt->disparity.view()(x, y);
      if (std::isfinite(d)) {
        ++valid;
        auto p = rectified_point(pair, x, y, d);
        ASSERT_TRUE(p.ok());
        // The point is the first surface on the left ray and visible from the right.
        const Eigen::Vector3d to_l = *p - cl, to_r = *p - cr;
        const auto hl = caster.first_hit(cl, to_l.normalized());
        const auto hr = caster.first_hit(cr, to_r.normalized());
        const bool on_left = std::abs(hl.t - to_l.norm()) < 1e-6 * to_l.norm();
        const bool seen_right = hr.t > to_r.norm() * (1 - 1e-6);
        // Its images in both original views map back to the rectified pair (u, v), (u - d, v).
        auto ul = project(s->rig.left, *p), ur = project(s->rig.right, *p);
        ASSERT_TRUE(ul && ur);
        auto rl = original_to_rectified(s->rig.left, pair.left, *ul);
        auto rr = original_to_rectified(s->rig.right, pair.right, *ur);
        ASSERT_TRUE(rl && rr);
        const double err = std::max((*rl - Eigen::Vector2d(x, y)).norm(),
                                    (*rr - Eigen::Vector2d(x - d, y)).norm());
        worst_px = std::max(worst_px, err);
        if (!on_left || !seen_right || err > 1e-3) ++bad_valid;
      } else {
        auto orig = rectified_to_original(s->rig.left, pair.left,
                                          {static_cast<double>(x), static_cast<double>(y)});
        ASSERT_TRUE(orig.ok());
        ++invalid;
        const Eigen::Vector3d dir =
            (pair.left.R.transpose() * Eigen::Vector3d((x - pair.left.cx_px) / pair.left.f_px,
                                                       (y - pair.left.cy_px) / pair.left.f_px, 1))
                .normalized();
        const auto hl = caster.first_hit(cl, dir);
        ASSERT_TRUE(hl.rock || hl.ground);
        // Invalid only because the right camera cannot see the point.
        const Eigen::Vector3d to_r = hl.point - cr;
        const auto hr = caster.first_hit(cr, to_r.normalized());
        const bool seen_right = hr.t > to_r.norm() * (1 - 1e-6);
        auto ur = project(s->rig.right, hl.point);
        const bool in_right =
            ur && ur->x() >= -0.5 && ur->x() <= 1023.5 && ur->y() >= -0.5 && ur->y() <= 767.5;
        if (seen_right && in_right) ++bad_invalid;
      }
    }
  std::printf("%d valid pixels (worst reprojection %.2e px), %d invalid; disagreements %d, %d\n",
              valid, worst_px, invalid, bad_valid, bad_invalid);
  EXPECT_GT(valid, 1000);
  EXPECT_GT(invalid, 20);  // the rock occludes some ground from the right camera
  EXPECT_EQ(bad_valid, 0);
  EXPECT_LE(bad_invalid, 2);  // rays grazing a rock edge may round either way
}

TEST(RenderGeometry, ShadowTruthMatchesIndependentShadowRays) {
  for (int k : {0, 13}) {  // low sun (long shadow) and high sun
    auto s = make_scene(flat_shaded(k));
    ASSERT_TRUE(s.ok()) << s.error().message;
    const TsaiCamera& cam = s->rig.left;
    const Rect win = rock_window(*s, cam, 6);
    const RenderedView v = render_view(*s, Eye::left, win);
    const check::IndependentCaster caster(*s);
    auto shadow_at = [&](double u, double w) {
      const Ray ray = pixel_to_ray(cam, {u, w});
      return caster.shadowed(caster.first_hit(ray.origin_mm, ray.direction));
    };
    // Independent shadow state at every pixel corner of the window.
    const int gw = win.w + 1;
    std::vector<char> corner(static_cast<std::size_t>(gw) * (win.h + 1));
    for (int j = 0; j <= win.h; ++j)
      for (int i = 0; i <= win.w; ++i)
        corner[static_cast<std::size_t>(j) * gw + i] = shadow_at(win.x + i - 0.5, win.y + j - 0.5);
    int interior = 0, interior_bad = 0, boundary = 0, boundary_bad = 0, shadow_px = 0;
    for (int j = 0; j < win.h; ++j)
      for (int i = 0; i < win.w; ++i) {
        const int x = win.x + i, y = win.y + j;
        const bool mask = v.shadow_mask.view()(x, y) == 255;
        shadow_px += mask ? 1 : 0;
        auto cr = [&](int a, int b) {
          return corner[static_cast<std::size_t>(j + b) * gw + (i + a)] != 0;
        };
        const bool c = cr(0, 0);
        if (cr(1, 0) == c && cr(0, 1) == c && cr(1, 1) == c && shadow_at(x, y) == c) {
          ++interior;
          interior_bad += mask != c ? 1 : 0;
          continue;
        }
        // Pixels a shadow edge crosses: the mask says "more than half in shadow".
        int n = 0;
        for (int b = 0; b < 6; ++b)
          for (int a = 0; a < 6; ++a)
            n += shadow_at(x - 0.5 + (a + 0.5) / 6, y - 0.5 + (b + 0.5) / 6) ? 1 : 0;
        const double cover = n / 36.0;
        if (cover < 0.35 || cover > 0.65) {
          ++boundary;
          boundary_bad += mask != (cover > 0.5) ? 1 : 0;
        }
      }
    std::printf(
        "scene %d: %d interior pixels (%d disagree), %d clear-cut edge pixels (%d disagree), "
        "%d shadow pixels\n",
        k, interior, interior_bad, boundary, boundary_bad, shadow_px);
    EXPECT_GT(shadow_px, 200);
    EXPECT_GT(boundary, 100);
    EXPECT_EQ(interior_bad, 0);
    EXPECT_EQ(boundary_bad, 0);
  }
}

}  // namespace
}  // namespace petra::sim
