#include "sim/score/score_report.hpp"

#include <cmath>
#include <cstdarg>
#include <cstdio>

#include "algo/core/json_writer.hpp"

namespace petra::sim {

namespace {

[[gnu::format(printf, 2, 3)]] void append(std::string& s, const char* fmt, ...) {
  char buf[512];
  va_list ap;
  va_start(ap, fmt);
  std::vsnprintf(buf, sizeof buf, fmt, ap);
  va_end(ap);
  s += buf;
}

std::string fraction(double v) {
  if (std::isnan(v)) return "n/a";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3f", v);
  return buf;
}

// One matched (or unmatched designed) facet against the limits.
void facet_failures(const FacetScore& f, const ScoreLimits& l, std::vector<std::string>& out) {
  std::string line;
  const bool wants_match = l.max_normal_deg || l.max_centroid_mm || l.require_on_facet;
  if (f.plane < 0) {
    if (wants_match) {
      line.clear();
      append(line, "facet %d: no plane matched", f.facet);
      out.push_back(line);
    }
    return;
  }
  if (l.max_normal_deg && f.normal_error_deg > *l.max_normal_deg) {
    line.clear();
    append(line, "facet %d: normal error %.2f deg > %.2f", f.facet, f.normal_error_deg,
           *l.max_normal_deg);
    out.push_back(line);
  }
  if (l.max_centroid_mm && f.centroid_plane_distance_mm > *l.max_centroid_mm) {
    line.clear();
    append(line, "facet %d: centroid %.2f mm off the facet plane > %.2f", f.facet,
           f.centroid_plane_distance_mm, *l.max_centroid_mm);
    out.push_back(line);
  }
  if (l.require_on_facet && !f.centroid_on_facet) {
    line.clear();
    append(line, "facet %d: centroid %.2f mm outside the facet", f.facet, f.centroid_outside_mm);
    out.push_back(line);
  }
}

}  // namespace

std::vector<std::string> limit_failures(const ScoreReport& r, const ScoreLimits& l) {
  std::vector<std::string> out;
  std::string line;
  if (r.planes) {
    const PlaneScore& p = *r.planes;
    if (l.require_count && !p.count_agrees) {
      line.clear();
      append(line, "plane count %d, truth %d", p.output_planes, p.truth_planes);
      out.push_back(line);
    }
    // Every plane must meet the limits, on a designed facet or on another one.
    for (const FacetScore& f : p.facets) facet_failures(f, l, out);
    for (const FacetScore& f : p.other_facets) facet_failures(f, l, out);
  }
  if (r.disparity) {
    if (l.max_bad1_pct && r.disparity->bad1_pct > *l.max_bad1_pct) {
      line.clear();
      append(line, "disparity bad-1 %.2f %% > %.2f", r.disparity->bad1_pct, *l.max_bad1_pct);
      out.push_back(line);
    }
    if (l.max_bad2_pct && r.disparity->bad2_pct > *l.max_bad2_pct) {
      line.clear();
      append(line, "disparity bad-2 %.2f %% > %.2f", r.disparity->bad2_pct, *l.max_bad2_pct);
      out.push_back(line);
    }
  }
  if (r.shadow) {
    // An undefined figure (nothing predicted or nothing true) fails its limit.
    if (l.min_shadow_precision && !(r.shadow->precision >= *l.min_shadow_precision)) {
      line.clear();
      append(line, "shadow precision %s < %.3f", fraction(r.shadow->precision).c_str(),
             *l.min_shadow_precision);
      out.push_back(line);
    }
    if (l.min_shadow_recall && !(r.shadow->recall >= *l.min_shadow_recall)) {
      line.clear();
      append(line, "shadow recall %s < %.3f", fraction(r.shadow->recall).c_str(),
             *l.min_shadow_recall);
      out.push_back(line);
    }
  }
  return out;
}

std::string format_score_text(const ScoreReport& r, const std::vector<std::string>& failures) {
  std::string s;
  if (r.planes) {
    const PlaneScore& p = *r.planes;
    append(s, "planes: %d output, %d in truth (%s)\n", p.output_planes, p.truth_planes,
           p.count_agrees ? "count agrees" : "COUNT DIFFERS");
    append(s, "%-6s %10s %6s %15s %17s %9s %11s\n", "facet", "area_mm2", "plane", "normal_err_deg",
           "centroid_dist_mm", "on_facet", "outside_mm");
    auto row = [&](const FacetScore& f) {
      const double area = static_cast<std::size_t>(f.facet) < r.facet_areas_mm2.size()
                              ? r.facet_areas_mm2[static_cast<std::size_t>(f.facet)]
                              : 0.0;
      if (f.plane < 0)
        append(s, "%-6d %10.1f %6s %15s %17s %9s %11s\n", f.facet, area, "-", "-", "-", "-", "-");
      else
        append(s, "%-6d %10.1f %6d %15.2f %17.2f %9s %11.2f\n", f.facet, area, f.plane,
               f.normal_error_deg, f.centroid_plane_distance_mm, f.centroid_on_facet ? "yes" : "no",
               f.centroid_outside_mm);
    };
    for (const FacetScore& f : p.facets) row(f);
    if (!p.other_facets.empty()) {
      append(s, "planes on other visible facets (not designed grind faces):\n");
      for (const FacetScore& f : p.other_facets) row(f);
    }
    if (!p.extra_planes.empty()) {
      append(s, "extra planes:");
      for (int j : p.extra_planes) append(s, " %d", j);
      append(s, "\n");
    }
    if (p.ground)
      append(s, "ground: normal error %.2f deg, height error under the rock %.2f mm\n",
             p.ground->normal_error_deg, p.ground->height_error_mm);
  }
  if (r.disparity) {
    const DisparityScore& d = *r.disparity;
    append(s,
           "disparity (region %d,%d,%d,%d; %ld px with truth): bad-1 %.2f %%, bad-2 %.2f %%, "
           "coverage %.2f %%, bad-1 of valid %.2f %%, mean |error| %.3f px\n",
           d.region.x, d.region.y, d.region.w, d.region.h, d.truth_pixels, d.bad1_pct, d.bad2_pct,
           d.coverage_pct, d.bad1_valid_pct, d.mean_abs_error_px);
  }
  if (r.shadow) {
    const MaskScore& m = *r.shadow;
    append(
        s,
        "shadow (region %d,%d,%d,%d): precision %s, recall %s, IoU %s (TP %ld, FP %ld, FN %ld)\n",
        m.region.x, m.region.y, m.region.w, m.region.h, fraction(m.precision).c_str(),
        fraction(m.recall).c_str(), fraction(m.iou).c_str(), m.true_positive, m.false_positive,
        m.false_negative);
  }
  if (failures.empty()) {
    s += "limits: all met\n";
  } else {
    for (const auto& f : failures) append(s, "LIMIT EXCEEDED: %s\n", f.c_str());
  }
  return s;
}

std::string format_score_json(const ScoreReport& r, const std::vector<std::string>& failures) {
  std::string buf(std::size_t{1} << 20, '\0');
  json::Writer w({buf.data(), buf.size()});
  // The writer turns a non-finite number into null.
  auto num = [&](const char* key, double v) { w.key(key).number(v); };
  w.begin_object();
  if (r.planes) {
    const PlaneScore& p = *r.planes;
    w.key("planes").begin_object();
    w.key("output").integer(p.output_planes);
    w.key("truth").integer(p.truth_planes);
    w.key("count_agrees").boolean(p.count_agrees);
    auto facet_array = [&](const char* key, const std::vector<FacetScore>& list) {
      w.key(key).begin_array();
      for (const FacetScore& f : list) {
        w.begin_object();
        w.key("facet").integer(f.facet);
        if (f.plane < 0) {
          w.key("plane").number(NAN);
        } else {
          w.key("plane").integer(f.plane);
          num("normal_error_deg", f.normal_error_deg);
          num("centroid_plane_distance_mm", f.centroid_plane_distance_mm);
          w.key("centroid_on_facet").boolean(f.centroid_on_facet);
          num("centroid_outside_mm", f.centroid_outside_mm);
        }
        w.end_object();
      }
      w.end_array();
    };
    facet_array("facets", p.facets);
    facet_array("other_facets", p.other_facets);
    w.key("extra_planes").begin_array();
    for (int j : p.extra_planes) w.integer(j);
    w.end_array();
    if (p.ground) {
      w.key("ground").begin_object();
      num("normal_error_deg", p.ground->normal_error_deg);
      num("height_error_mm", p.ground->height_error_mm);
      w.end_object();
    }
    w.end_object();
  }
  auto region = [&](const Rect& g) {
    w.key("region").begin_array().integer(g.x).integer(g.y).integer(g.w).integer(g.h).end_array();
  };
  if (r.disparity) {
    const DisparityScore& d = *r.disparity;
    w.key("disparity").begin_object();
    region(d.region);
    w.key("truth_pixels").integer(d.truth_pixels);
    w.key("valid_pixels").integer(d.valid_pixels);
    num("bad1_pct", d.bad1_pct);
    num("bad2_pct", d.bad2_pct);
    num("coverage_pct", d.coverage_pct);
    num("bad1_valid_pct", d.bad1_valid_pct);
    num("mean_abs_error_px", d.mean_abs_error_px);
    w.end_object();
  }
  if (r.shadow) {
    const MaskScore& m = *r.shadow;
    w.key("shadow").begin_object();
    region(m.region);
    w.key("true_positive").integer(m.true_positive);
    w.key("false_positive").integer(m.false_positive);
    w.key("false_negative").integer(m.false_negative);
    num("precision", m.precision);
    num("recall", m.recall);
    num("iou", m.iou);
    w.end_object();
  }
  w.key("limits_met").boolean(failures.empty());
  w.key("failures").begin_array();
  for (const auto& f : failures) w.string(f);
  w.end_array();
  w.end_object();
  w.raw("\n");
  auto n = w.finish();
  return n ? std::string(buf.data(), *n) : std::string("{\"error\":\"report too large\"}\n");
}

}  // namespace petra::sim
