#include "sim/scene/scene_truth.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "algo/camera/calib_json.hpp"
#include "algo/core/json_writer.hpp"
#include "sim/io/json_vec3.hpp"
#include "sim/scene/truth_pixels.hpp"

namespace petra::sim {

namespace {

Rect clip_box(double u0, double v0, double u1, double v1, int w, int h) {
  const int x0 = std::max(0, static_cast<int>(std::floor(u0)));
  const int y0 = std::max(0, static_cast<int>(std::floor(v0)));
  const int x1 = std::min(w - 1, static_cast<int>(std::ceil(u1)));
  const int y1 = std::min(h - 1, static_cast<int>(std::ceil(v1)));
  return {x0, y0, x1 - x0 + 1, y1 - y0 + 1};
}

Rect left_roi(const Scene& s, const ConvexRock& rock) {
  auto pts = rock_outline_points(rock, 16);
  const auto shadow = polygon_edge_points(shadow_region(rock, s.sun_dir), 16);
  pts.insert(pts.end(), shadow.begin(), shadow.end());
  double u0 = INFINITY, v0 = INFINITY, u1 = -INFINITY, v1 = -INFINITY;
  for (const auto& p : pts) {
    auto uv = project(s.rig.left, p);
    if (!uv) continue;
    u0 = std::min(u0, uv->x());
    v0 = std::min(v0, uv->y());
    u1 = std::max(u1, uv->x());
    v1 = std::max(v1, uv->y());
  }
  // A margin of ground all round: 12 % of the larger side, at least 20 px.
  const double m = std::max(20.0, 0.12 * std::max(u1 - u0, v1 - v0));
  return clip_box(u0 - m, v0 - m, u1 + m, v1 + m, s.rig.left.width, s.rig.left.height);
}

Rect rectified_box(const Scene& s, const RectifiedPair& pair, const Rect& roi) {
  double u0 = INFINITY, v0 = INFINITY, u1 = -INFINITY, v1 = -INFINITY;
  auto add = [&](double u, double v) {
    auto r = original_to_rectified(s.calib_rig.left, pair.left, {u, v});
    if (!r) return;
    u0 = std::min(u0, r->x());
    v0 = std::min(v0, r->y());
    u1 = std::max(u1, r->x());
    v1 = std::max(v1, r->y());
  };
  // Distortion bends the ROI's sides: walk along them.
  for (int x = roi.x; x < roi.x + roi.w; ++x) {
    add(x, roi.y);
    add(x, roi.y + roi.h - 1);
  }
  for (int y = roi.y; y < roi.y + roi.h; ++y) {
    add(roi.x, y);
    add(roi.x + roi.w - 1, y);
  }
  return clip_box(u0, v0, u1, v1, pair.left.width, pair.left.height);
}

// RMS of the finite values of `img` inside `r` (-1 when none), and their largest |value|.
double rms_in(const io::FloatImage& img, const Rect& r, double* max_abs = nullptr) {
  if (img.data.empty()) return -1;
  double sum2 = 0, peak = 0;
  long n = 0;
  const auto view = img.view();
  for (int y = r.y; y < r.y + r.h; ++y)
    for (int x = r.x; x < r.x + r.w; ++x) {
      const double v = view(x, y);
      if (!std::isfinite(v)) continue;
      sum2 += v * v;
      peak = std::max(peak, std::abs(v));
      ++n;
    }
  if (max_abs) *max_abs = peak;
  return n ? std::sqrt(sum2 / static_cast<double>(n)) : -1;
}

void rect(json::Writer& w, const Rect& r) {
  w.begin_array().integer(r.x).integer(r.y).integer(r.w).integer(r.h).end_array();
}

// A facet's geometry in the world frame (the contract's facet fields).
void write_facet(json::Writer& w, const Scene& s, const VisibleFacet& f) {
  w.key("normal");
  write_vec3(w, dir_to_world(s, f.normal));
  w.key("centroid_mm");
  write_vec3(w, to_world(s, f.centroid));
  w.key("polygon_mm").begin_array();
  for (const auto& p : f.polygon) write_vec3(w, to_world(s, p));
  w.end_array();
  w.key("visible_area_mm2").number(f.area_mm2);
  w.key("grind_face").boolean(f.grind_face);
}

// The rocks touching the target (never truth facets).
void write_neighbours(json::Writer& w, const Scene& s) {
  w.key("neighbours").begin_array();
  for (std::size_t k = 0; k < s.neighbours.size(); ++k) {
    w.begin_object();
    w.key("centre_mm");
    write_vec3(w, to_world(s, s.neighbours[k].centre));
    w.key("radius_mm").number(s.neighbours[k].radius_mm);
    w.key("gap_max_mm").number(s.neighbour_gap_mm[k]);
    w.end_object();
  }
  w.end_array();
}

// The realistic world's knobs and what was measured on the rendered scene.
Status write_world(json::Writer& w, const Scene& s, const SceneTruth& t) {
  const World& o = s.options.world;
  w.raw("\n");
  w.key("world").begin_object();
  w.key("relief_rms_mm").number(o.relief_rms_mm);
  w.key("relief_rms_roi_mm").number(t.relief_rms_roi_mm);
  w.key("pebble_cover").number(o.pebble_cover);
  w.key("stones_per_m2").number(o.stones_per_m2);
  w.key("stones").integer(static_cast<long long>(s.stones.size()));
  w.key("slope_deg").number(o.slope_deg);
  w.key("slope_azimuth_deg").number(s.slope_azimuth_deg);
  w.key("face_roughness_mm").number(o.face_roughness_mm);
  w.key("face_curvature_per_m").number(o.face_curvature_per_m);
  w.key("gain").begin_array().number(o.gain_left).number(o.gain_right).end_array();
  w.key("offset_dn").begin_array().number(o.offset_left_dn).number(o.offset_right_dn).end_array();
  w.key("vignetting").number(o.vignetting);
  w.key("prnu").number(o.prnu);
  if (o.burial) w.key("burial").number(*o.burial);
  w.end_object();
  w.raw("\n");
  w.key("calibration").begin_object();
  w.key("residual_px").number(s.calib_residual_px);
  w.key("configured_residual_px").number(o.calib_residual_px);
  w.key("vertical_disparity_rms_px").number(t.vertical_rms_px);
  w.key("vertical_disparity_max_px").number(t.vertical_max_px);
  std::vector<char> buf(16384);
  auto n = format_calib_json(s.true_rig_world, {buf.data(), buf.size()});
  if (!n) return n.error();
  std::string_view rig(buf.data(), *n);
  while (!rig.empty() && (rig.back() == '\n' || rig.back() == ' ')) rig.remove_suffix(1);
  w.key("true_rig").raw(rig);  // last: raw text sets no separator
  w.end_object();
  return {};
}

// Every rock's truth: rock 0 as above, each further rock with its own ROI and click.
void add_rock_truths(const Scene& s, SceneTruth& t) {
  RockTruth first;
  first.roi = t.roi;
  first.click = t.click;
  first.facets = t.facets;
  judge_rock(s, 0, first);
  t.rocks.push_back(std::move(first));
  for (int r = 1; r < rock_count(s); ++r) {
    RockTruth rt = further_rock_truth(s, r);
    rt.roi = left_roi(s, rock_at(s, r));
    rt.click = click_on_rock(s, rt.roi, rt.facets, r);
    if (!rt.click) rt.click = pixel_on_rock(s, rt.roi, r);
    t.rocks.push_back(std::move(rt));
  }
}

void write_rock(json::Writer& w, const Scene& s, const RockTruth& r, int id) {
  w.raw("\n ");
  w.begin_object();
  w.key("id").integer(id);
  w.key("kind").string(
      id == 0 ? "target" : rock_kind_name(s.neighbour_kind[static_cast<std::size_t>(id - 1)]));
  w.key("roi");
  rect(w, r.roi);
  if (r.click) w.key("click").begin_array().integer(r.click->x()).integer(r.click->y()).end_array();
  w.key("height_mm").number(r.height_mm);
  w.key("size_mm").number(r.size_mm);
  w.key("facets").begin_array();
  for (std::size_t i = 0; i < r.facets.size(); ++i) {
    const VisibleFacet& f = r.facets[i];
    const FacetJudgement& j = r.judged[i];
    w.raw("\n  ");
    w.begin_object();
    write_facet(w, s, f);
    w.key("grindable").boolean(j.grindable);
    w.key("reason").string(j.reason);
    w.key("disc_rms_mm").number(j.disc_rms_mm);
    w.key("reachable").boolean(j.reachable);
    w.key("reach_reason").string(arm::arm_reason_name(j.reach));
    if (j.reach_disc_centre) {  // out of reach at the centroid, not at this grindable disc
      w.key("reach_disc_mm");
      write_vec3(w, to_world(s, *j.reach_disc_centre));
    }
    w.end_object();
  }
  w.end_array();
  w.end_object();
}

}  // namespace

SceneTruth compute_truth(const Scene& s, const RectifiedTruth& rect_truth) {
  SceneTruth t;
  t.planes = s.flat_faces;
  t.facets = visible_facets(s);
  t.roi = left_roi(s, s.rock);
  if (s.options.roi_fill) t.roi = roi_inside_rock(s, t.roi);
  t.click = click_on_rock(s, t.roi, t.facets);
  t.roi_rectified = rectified_box(s, rect_truth.pair, t.roi);
  double lo = INFINITY, hi = -INFINITY;
  const auto view = rect_truth.disparity.view();
  for (int y = t.roi_rectified.y; y < t.roi_rectified.y + t.roi_rectified.h; ++y)
    for (int x = t.roi_rectified.x; x < t.roi_rectified.x + t.roi_rectified.w; ++x) {
      const double d = view(x, y);
      if (!std::isfinite(d)) continue;
      lo = std::min(lo, d);
      hi = std::max(hi, d);
    }
  t.disparity_min = std::isfinite(lo) ? lo : 0.0;
  t.disparity_max = std::isfinite(hi) ? hi : 0.0;
  if (s.face_relief.active)
    for (auto& f : t.facets)
      t.fits.push_back(fit_facet(f, rect_truth.face_points[static_cast<std::size_t>(f.face)]));
  t.relief_rms_roi_mm = rms_in(rect_truth.surface_height, t.roi_rectified);
  if (!rect_truth.vertical.data.empty())
    t.vertical_rms_px = rms_in(rect_truth.vertical, t.roi_rectified, &t.vertical_max_px);
  if (s.options.rocks > 1) add_rock_truths(s, t);
  return t;
}

Result<std::string> format_truth_json(const Scene& s, const SceneTruth& t) {
  std::vector<char> buf(std::size_t{1} << 20);
  json::Writer w({buf.data(), buf.size()});
  w.begin_object();
  w.key("roi");
  rect(w, t.roi);
  w.raw("\n");
  w.key("planes").integer(t.planes);
  w.key("facets").begin_array();
  for (const auto& f : t.facets) {
    w.raw("\n ");
    w.begin_object();
    write_facet(w, s, f);
    const std::size_t i = static_cast<std::size_t>(&f - t.facets.data());
    if (i < t.fits.size() && t.fits[i].fitted) {
      w.key("flatness_rms_mm").number(t.fits[i].flatness_rms_mm);
      w.key("fit_points").integer(t.fits[i].points);
    }
    w.end_object();
  }
  w.end_array();
  w.raw("\n");
  // Ground plane n.X + d = 0 (world frame: the ground is z = 0).
  w.key("ground").begin_object();
  const Eigen::Vector3d ground_n = dir_to_world(s, Eigen::Vector3d::UnitZ());
  w.key("normal");
  write_vec3(w, ground_n);
  w.key("d_mm").number(s.tilted ? -ground_n.dot(s.pivot) : 0.0);
  w.end_object();
  w.raw("\n");
  w.key("sun_dir");
  write_vec3(w, dir_to_world(s, s.sun_dir));
  w.key("seed").integer(static_cast<long long>(s.options.seed));
  w.raw("\n");
  w.key("roi_rectified");
  rect(w, t.roi_rectified);
  w.key("disparity_range")
      .begin_array()
      .number(t.disparity_min)
      .number(t.disparity_max)
      .end_array();
  if (t.click) w.key("click").begin_array().integer(t.click->x()).integer(t.click->y()).end_array();
  w.raw("\n");
  w.key("scene").begin_object();
  w.key("boundary").string(boundary_name(s.boundary));
  w.key("shape").string(shape_name(s.shape));
  w.key("flat_faces").integer(s.flat_faces);
  w.key("sun_elevation_deg").number(s.sun_elevation_deg);
  w.key("sun_azimuth_deg").number(s.sun_azimuth_deg);
  w.key("rock_size_mm").number(s.rock_size_mm);
  w.key("rock_distance_mm").number(s.rock_distance_mm);
  w.key("camera_height_mm").number(s.camera_height_mm);
  w.key("tone_ratio").number(s.tone_ratio);
  w.key("rock_centre_mm");
  write_vec3(w, to_world(s, s.rock_centre_mm));
  w.key("noise_dn").number(s.options.noise_sigma_dn);
  w.key("texture").boolean(s.options.texture);
  if (s.options.roi_fill) w.key("roi_fill").boolean(true);
  if (!s.neighbours.empty()) write_neighbours(w, s);
  w.end_object();
  if (!t.rocks.empty()) {
    w.raw("\n");
    w.key("rocks").begin_array();
    for (std::size_t r = 0; r < t.rocks.size(); ++r)
      write_rock(w, s, t.rocks[r], static_cast<int>(r));
    w.end_array();
  }
  if (!is_clean(s.options.world)) PETRA_TRY(write_world(w, s, t));
  w.end_object();
  w.raw("\n");
  auto n = w.finish();
  if (!n) return n.error();
  return std::string(buf.data(), *n);
}

}  // namespace petra::sim
