#include "sim/demo/demo_report.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "sim/score/planes_file.hpp"
#include "sim/score/score_report.hpp"
#include "sim/score/truth_file.hpp"

namespace petra::demo {

namespace {

constexpr const char* kStepNames[] = {"acquire",     "rectify", "shadow", "match",
                                      "reconstruct", "segment", "planes", "products"};

std::vector<tlm::GrindPlane> ranked(const Received& r) {
  std::vector<tlm::GrindPlane> p = r.planes;
  std::sort(p.begin(), p.end(), [](const auto& a, const auto& b) { return a.rank < b.rank; });
  return p;
}

// "(x, y, z)" with `decimals` digits after the point.
std::string vec3(const std::array<double, 3>& v, int decimals) {
  char s[96];
  std::snprintf(s, sizeof s, "(%.*f, %.*f, %.*f)", decimals, v[0], decimals, v[1], decimals, v[2]);
  return s;
}

}  // namespace

void print_received(const Received& r, std::FILE* out) {
  const auto planes = ranked(r);
  std::fprintf(out, "   %-4s  %-27s  %-26s  %9s  %13s  %9s\n", "rank", "normal (out of the rock)",
               "centroid mm", "area mm2", "flatness mm", "triangles");
  for (const auto& p : planes)
    std::fprintf(out, "   %-4u  %-27s  %-26s  %9.0f  %13.2f  %9u\n", p.rank + 1u,
                 vec3(p.normal, 3).c_str(), vec3(p.centroid_mm, 1).c_str(), p.area_mm2,
                 p.flatness_rms_mm, p.triangles);
  if (planes.empty()) std::fprintf(out, "   (no plane qualified)\n");
  if (r.ground)
    std::fprintf(out, "   ground: normal (%.4f, %.4f, %.4f), d %.1f mm, %u points\n",
                 r.ground->normal[0], r.ground->normal[1], r.ground->normal[2], r.ground->d_mm,
                 r.ground->points);
  if (!r.result) return;
  const tlm::EvalResult& e = *r.result;
  std::fprintf(out, "   dense points %u, after the mean filter %u, disparity %.1f .. %.1f px\n",
               e.dense_points, e.filtered_points, static_cast<double>(e.disparity_min),
               static_cast<double>(e.disparity_max));
  std::fprintf(out, "   time per step (ms):");
  for (std::size_t i = 0; i < e.step_us.size(); ++i)
    std::fprintf(out, "%s %s %.1f", i == 0 ? "" : " |", kStepNames[i], e.step_us[i] / 1000.0);
  std::fprintf(out, "\n   total %u ms on board\n", e.total_ms);
}

std::string planes_json(const Received& r) {
  std::string s = "{\"planes\":[";
  char b[400];
  bool first = true;
  for (const auto& p : ranked(r)) {
    std::snprintf(b, sizeof b,
                  "%s{\"normal\":[%.17g,%.17g,%.17g],\"centroid_mm\":[%.17g,%.17g,%.17g],"
                  "\"area_mm2\":%.17g,\"rms_mm\":%.17g,\"triangles\":%u}",
                  first ? "" : ",", p.normal[0], p.normal[1], p.normal[2], p.centroid_mm[0],
                  p.centroid_mm[1], p.centroid_mm[2], p.area_mm2, p.flatness_rms_mm, p.triangles);
    s += b;
    first = false;
  }
  s += "]";
  if (r.ground) {
    std::snprintf(b, sizeof b, ",\"ground\":{\"normal\":[%.17g,%.17g,%.17g],\"d_mm\":%.17g}",
                  r.ground->normal[0], r.ground->normal[1], r.ground->normal[2], r.ground->d_mm);
    s += b;
  }
  if (r.result) {
    std::snprintf(b, sizeof b,
                  ",\"stats\":{\"dense_points\":%u,\"filtered_points\":%u,\"disparity_min\":%.9g,"
                  "\"disparity_max\":%.9g}",
                  r.result->dense_points, r.result->filtered_points,
                  static_cast<double>(r.result->disparity_min),
                  static_cast<double>(r.result->disparity_max));
    s += b;
  }
  return s + "}\n";
}

bool same_planes(const std::string& a, const std::string& b) {
  auto pa = sim::parse_planes_json(a);
  auto pb = sim::parse_planes_json(b);
  if (!pa || !pb || pa->planes.size() != pb->planes.size()) return false;
  for (std::size_t i = 0; i < pa->planes.size(); ++i) {
    const auto& x = pa->planes[i];
    const auto& y = pb->planes[i];
    if (x.normal != y.normal || x.grind_point() != y.grind_point() || x.area_mm2 != y.area_mm2 ||
        x.rms_mm != y.rms_mm || x.triangles != y.triangles)
      return false;
  }
  if (pa->ground.has_value() != pb->ground.has_value()) return false;
  return !pa->ground ||
         (pa->ground->normal == pb->ground->normal && pa->ground->d_mm == pb->ground->d_mm);
}

bool score_and_print(const std::string& truth_json, const std::string& planes_json_text,
                     const DemoLimits& limits, std::FILE* out) {
  auto truth = sim::parse_truth_json(truth_json);
  if (!truth) {
    std::fprintf(out, "   cannot score: %s\n", truth.error().message);
    return false;
  }
  auto planes = sim::parse_planes_json(planes_json_text);
  if (!planes) {
    std::fprintf(out, "   cannot score: %s\n", planes.error().message);
    return false;
  }
  sim::ScoreReport report;
  report.planes = sim::score_planes(*truth, *planes);
  for (const auto& f : truth->facets) report.facet_areas_mm2.push_back(f.visible_area_mm2);
  sim::ScoreLimits l;
  l.max_normal_deg = limits.max_normal_deg;
  l.max_centroid_mm = limits.max_centroid_mm;
  l.require_on_facet = true;
  const auto failures = sim::limit_failures(report, l);
  std::string text = sim::format_score_text(report, failures);
  for (std::size_t at = 0; at < text.size();) {  // indent the scorer's table
    const std::size_t nl = text.find('\n', at);
    const std::size_t end = nl == std::string::npos ? text.size() : nl;
    std::fprintf(out, "   %s\n", text.substr(at, end - at).c_str());
    at = end + 1;
  }
  std::fprintf(
      out,
      "   verdict: %s (each truth face matched, normal within %.0f deg, centroid within %.0f mm "
      "of the face's plane and on it)\n",
      failures.empty() ? "PASS" : "FAIL", limits.max_normal_deg, limits.max_centroid_mm);
  return failures.empty();
}

}  // namespace petra::demo
