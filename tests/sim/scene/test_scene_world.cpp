// The realistic world's knobs (docs/scene.md "Realistic world"), each checked
// against what is rendered: the relief's RMS, stones the rays hit, the
// slope's ground plane, rough faces' flatness, camera gain/offset and
// vignetting, the calibration residual in pixels; bad values are refused
// naming the option; the clean world is unchanged.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "algo/camera/rectify_geometry.hpp"
#include "sim/scene/camera_rays.hpp"
#include "sim/scene/ray_cast.hpp"
#include "sim/scene/scene_render.hpp"
#include "sim/scene/scene_set.hpp"
#include "sim/scene/terrain.hpp"
#include "sim/scene/world_builder.hpp"

namespace petra::sim {
namespace {

SceneOptions base(std::uint64_t seed = 1003) {
  SceneOptions o = standard_scene_set()[3];
  o.seed = seed;
  return o;
}

TEST(SceneWorld, BadKnobsAreRefusedNamingTheOption) {
  struct Case {
    void (*set)(World&);
    const char* name;
  };
  const Case cases[] = {
      {[](World& w) { w.relief_rms_mm = 11; }, "relief"},
      {[](World& w) { w.pebble_cover = -0.1; }, "pebbles"},
      {[](World& w) { w.stones_per_m2 = 1e4; }, "stones"},
      {[](World& w) { w.slope_deg = 25; }, "slope"},
      {[](World& w) { w.slope_azimuth_deg = NAN; }, "slope-azimuth"},
      {[](World& w) { w.face_roughness_mm = 3; }, "face-roughness"},
      {[](World& w) { w.face_curvature_per_m = -1; }, "face-curvature"},
      {[](World& w) { w.gain_left = 0.2; }, "gain-left"},
      {[](World& w) { w.gain_right = 2; }, "gain-right"},
      {[](World& w) { w.offset_left_dn = -50; }, "offset-left"},
      {[](World& w) { w.offset_right_dn = 41; }, "offset-right"},
      {[](World& w) { w.vignetting = 0.9; }, "vignetting"},
      {[](World& w) { w.prnu = 0.5; }, "prnu"},
      {[](World& w) { w.calib_residual_px = 5; }, "calib-residual"},
      {[](World& w) { w.burial = 0.9; }, "burial"},
  };
  for (const Case& c : cases) {
    SceneOptions o = base();
    o.world = realistic_world();
    c.set(o.world);
    const Status st = validate(o);
    ASSERT_FALSE(st.ok()) << c.name;
    EXPECT_EQ(std::string(st.error().message).rfind(std::string(c.name) + " = ", 0), 0u)
        << st.error().message;
  }
  SceneOptions o = base();
  o.world = realistic_world();
  EXPECT_TRUE(validate(o).ok());
  EXPECT_TRUE(is_clean(World{}));
  EXPECT_FALSE(is_clean(realistic_world()));
  for (const SceneOptions& r : real_scene_set()) EXPECT_TRUE(validate(r).ok());
}

// The tabulated relief has the chosen RMS over the full-relief disc.
TEST(SceneWorld, TerrainReliefHasTheChosenRms) {
  World w;
  w.relief_rms_mm = 2.5;
  const Terrain t = make_terrain(w, 7, {100, 700});
  ASSERT_TRUE(t.active);
  double sum2 = 0, sum = 0;
  int n = 0;
  for (double y = -690; y <= 690; y += 5)
    for (double x = -690; x <= 690; x += 5) {
      if (x * x + y * y > 690.0 * 690.0) continue;
      const double h = terrain_height(t, 100 + x, 700 + y);
      sum += h;
      sum2 += h * h;
      ++n;
    }
  EXPECT_NEAR(std::sqrt(sum2 / n), 2.5, 0.1);
  EXPECT_NEAR(sum / n, 0.0, 0.3);
  // Far from the rock the ground is the plane again.
  EXPECT_EQ(terrain_height(t, 100 + 950, 700), 0.0);
}

// Pebbles are geometry: a vertical ray onto a pebble's top stops above the relief.
TEST(SceneWorld, PebblesAreHitByRays) {
  World w;
  w.pebble_cover = 0.2;
  const Terrain t = make_terrain(w, 9, {0, 600});
  int pebbles = 0, checked = 0;
  for (double y = 400; y < 800 && checked < 400; y += 1.3)
    for (double x = -200; x < 200 && checked < 400; x += 1.7) {
      const double h = terrain_height(t, x, y);
      if (h < 1.0) continue;
      ++checked;
      double hit = 0;
      const Eigen::Vector3d o(x + 30, y, 60), d = Eigen::Vector3d(-30, 0, h - 60).normalized();
      ASSERT_TRUE(ray_hits_terrain(t, o, d, 0, 1e4, hit));
      const Eigen::Vector3d p = o + hit * d;
      // The first surface met is at or before the pebble's top point.
      EXPECT_LE(hit, (Eigen::Vector3d(x, y, h) - o).norm() + 1e-3);
      EXPECT_NEAR(p.z(), terrain_height(t, p.x(), p.y()), 2e-3);
      pebbles += 1;
    }
  EXPECT_GT(pebbles, 50);
}

// A rendered realistic scene and what its knobs must give: the relief RMS in
// the ROI, the slope's ground plane through the disparity truth, the
// calibration residual, stones, rough faces, the disparity truth through the
// true cameras. One test renders it once for every check: ctest runs each test
// in a process of its own, and the render takes about a minute under ASan.
SceneProducts render_real_scene() {
  SceneOptions o = base(1006);
  o.world.relief_rms_mm = 2;
  o.world.slope_deg = 10;
  o.world.stones_per_m2 = 40;
  o.world.face_roughness_mm = 0.4;
  o.world.calib_residual_px = 0.3;
  o.edge_supersampling = 2;
  auto r = render_scene(o);
  EXPECT_TRUE(r.ok()) << r.error().message;
  return r.ok() ? std::move(*r) : SceneProducts{};
}

void check_real_relief_rms(const SceneProducts& p) {
  // The ROI's ground is a few hundred mm across: the largest wavelengths
  // (256 mm) make its RMS differ from the whole field's.
  EXPECT_NEAR(p.truth.relief_rms_roi_mm, 2.0, 0.8);
}

void check_real_calibration_residual(const SceneProducts& p) {
  const Scene& s = p.scene;
  EXPECT_NEAR(s.calib_residual_px, 0.3, 1e-3);
  // Measured again over other points of the scene.
  const double again =
      reprojection_rms_px(s.calib_rig, s.true_rig_world, visible_world_points(s, 7));
  EXPECT_NEAR(again, 0.3, 0.05);
  EXPECT_NE(s.calib_rig.right.cx_px, s.true_rig_world.right.cx_px);
  EXPECT_GT(p.truth.vertical_rms_px, 0.0);
}

void check_real_sloped_ground(const SceneProducts& p) {
  const Scene& s = p.scene;
  ASSERT_TRUE(s.tilted);
  const Eigen::Vector3d n = dir_to_world(s, Eigen::Vector3d::UnitZ());
  EXPECT_NEAR(std::acos(n.z()) * 180 / M_PI, 10.0, 1e-9);
  // Ground points the left camera sees, in the world frame, lie on the truth
  // plane within the relief.
  const CameraRays rays(s.rig.left);
  double sum2 = 0;
  int count = 0;
  for (int j = 400; j < 760; j += 9)
    for (int i = 10; i < 1010; i += 9) {
      const SceneHit hit = trace(s, rays.origin(), rays.direction(i, j));
      if (hit.surface != kGround) continue;
      const Eigen::Vector3d w = to_world(s, hit.point);
      const double dist = n.dot(w - s.pivot);
      EXPECT_NEAR(dist, hit.point.z(), 1e-6);
      sum2 += dist * dist;
      ++count;
    }
  ASSERT_GT(count, 1000);
  EXPECT_LT(std::sqrt(sum2 / count), 6.0);
}

void check_real_stones_and_rough_faces(const SceneProducts& p) {
  const Scene& s = p.scene;
  ASSERT_GT(s.stones.size(), 5u);
  int hits = 0;
  const Eigen::Vector3d cl = camera_centre_world(s.rig.left);
  for (const auto& stone : s.stones) {
    const Eigen::Vector3d top = stone.centre + Eigen::Vector3d(0, 0, 0.3 * stone.radius_mm);
    const SceneHit hit = trace(s, cl, (top - cl).normalized());
    hits += hit.surface >= kStone0 ? 1 : 0;
  }
  EXPECT_GT(hits, static_cast<int>(s.stones.size()) / 2);
  ASSERT_EQ(p.truth.fits.size(), p.truth.facets.size());
  for (int i = 0; i < s.flat_faces; ++i) {
    const FacetFit& f = p.truth.fits[static_cast<std::size_t>(i)];
    ASSERT_TRUE(f.fitted);
    EXPECT_GT(f.points, 500);
    EXPECT_NEAR(f.flatness_rms_mm, 0.4, 0.15) << "facet " << i;
    const Eigen::Vector3d base_n =
        s.rock.faces[static_cast<std::size_t>(p.truth.facets[static_cast<std::size_t>(i)].face)]
            .plane.normal;
    EXPECT_LT(
        std::acos(std::min(1.0, base_n.dot(p.truth.facets[static_cast<std::size_t>(i)].normal))) *
            180 / M_PI,
        1.0);
  }
}

// Every valid disparity truth pixel maps, through the true cameras, to the
// same scene point from both views.
void check_real_disparity_truth(const SceneProducts& p) {
  const Scene& s = p.scene;
  const auto& pair = p.rectified.pair;
  int checked = 0;
  const Rect r = p.truth.roi_rectified;
  for (int v = r.y; v < r.y + r.h; v += 11)
    for (int u = r.x; u < r.x + r.w; u += 11) {
      const float d = p.rectified.disparity.view()(u, v);
      if (!std::isfinite(d)) continue;
      const float dv = p.rectified.vertical.view()(u, v);
      auto ol = rectified_to_original(s.calib_rig.left, pair.left, {double(u), double(v)});
      auto orr =
          rectified_to_original(s.calib_rig.right, pair.right, {u - double(d), v + double(dv)});
      ASSERT_TRUE(ol.ok() && orr.ok());
      const CameraRays rl(s.rig.left);
      const SceneHit hit = trace(s, rl.origin(), rl.direction(ol->x(), ol->y()));
      auto back = project(s.rig.right, hit.point);
      ASSERT_TRUE(back.ok());
      EXPECT_LT((*back - *orr).norm(), 1e-3);
      ++checked;
    }
  EXPECT_GT(checked, 100);
}

TEST(RealScene, EveryKnobRendersAsConfigured) {
  const SceneProducts p = render_real_scene();
  ASSERT_FALSE(p.truth.facets.empty()) << "the realistic scene did not render";
  {
    SCOPED_TRACE("relief RMS in the ROI");
    check_real_relief_rms(p);
  }
  {
    SCOPED_TRACE("calibration residual");
    check_real_calibration_residual(p);
  }
  {
    SCOPED_TRACE("sloped ground plane");
    check_real_sloped_ground(p);
  }
  {
    SCOPED_TRACE("stones and rough faces");
    check_real_stones_and_rough_faces(p);
  }
  {
    SCOPED_TRACE("disparity truth through the true cameras");
    check_real_disparity_truth(p);
  }
}

// A partly buried rock: the ground cuts it at the chosen share of its height,
// and the rest of the scene (rig, sun) is the same seed's.
TEST(SceneWorld, BurialSinksTheRock) {
  SceneOptions o = base(1004);
  o.world.burial = 0.5;
  auto buried = make_scene(o);
  ASSERT_TRUE(buried.ok()) << buried.error().message;
  double zmin = INFINITY, zmax = -INFINITY;
  for (const auto& f : buried->rock.faces)
    for (const auto& p : f.polygon) {
      zmin = std::min(zmin, p.z());
      zmax = std::max(zmax, p.z());
    }
  EXPECT_NEAR(-zmin / (zmax - zmin), 0.5, 1e-9);
  EXPECT_EQ(buried->sun_elevation_deg, make_scene(base(1004))->sun_elevation_deg);
}

// Per-camera gain and offset, and vignetting, applied to the rendered DN.
TEST(SceneWorld, GainOffsetAndVignettingAreApplied) {
  SceneOptions plain = base(1011);
  plain.noise_sigma_dn = 0;
  SceneOptions changed = plain;
  changed.world.gain_right = 0.8;
  changed.world.offset_right_dn = 10;
  auto a = make_scene(plain), b = make_scene(changed);
  ASSERT_TRUE(a.ok() && b.ok());
  const Rect win{300, 300, 200, 100};
  const RenderedView ra = render_view(*a, Eye::right, win), rb = render_view(*b, Eye::right, win);
  const RenderedView la = render_view(*a, Eye::left, win), lb = render_view(*b, Eye::left, win);
  EXPECT_EQ(la.image.pixels, lb.image.pixels);  // the left camera is untouched
  for (int y = win.y; y < win.y + win.h; ++y)
    for (int x = win.x; x < win.x + win.w; ++x) {
      const double v = ra.image.view()(x, y), w = rb.image.view()(x, y);
      if (v < 250) {
        ASSERT_NEAR(w, 0.8 * v + 10, 1.0) << x << "," << y;
      }
    }
  SceneOptions vig = plain;
  vig.world.vignetting = 0.3;
  auto c = make_scene(vig);
  ASSERT_TRUE(c.ok());
  const Rect corner{0, 0, 40, 30};
  const RenderedView ca = render_view(*a, Eye::left, corner),
                     cc = render_view(*c, Eye::left, corner);
  const TsaiCamera& cam = a->rig.left;
  const double dx = std::max(cam.cx_px, 1023 - cam.cx_px),
               dy = std::max(cam.cy_px, 767 - cam.cy_px);
  for (int y = 0; y < 30; ++y)
    for (int x = 0; x < 40; ++x) {
      const double r2 =
          (std::pow(x - cam.cx_px, 2) + std::pow(y - cam.cy_px, 2)) / (dx * dx + dy * dy);
      ASSERT_NEAR(cc.image.view()(x, y), ca.image.view()(x, y) * (1 - 0.3 * r2), 1.0);
    }
}

}  // namespace
}  // namespace petra::sim
