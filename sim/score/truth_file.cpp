#include "sim/score/truth_file.hpp"

#include <string>

#include "sim/score/json_fields.hpp"

namespace petra::sim {

namespace {

Result<Rect> read_rect(const JsonFile& f, std::uint32_t i, const std::string& path) {
  const json::Token& t = f.doc().token(i);
  if (t.type != json::Type::array || t.count != 4) return f.error(path, "expected [x, y, w, h]");
  int v[4];
  const auto el = f.elements(i);
  for (int k = 0; k < 4; ++k) {
    auto n = f.integer(el[static_cast<std::size_t>(k)], path);
    if (!n) return n.error();
    if (*n < 0 || *n > 65535) return f.error(path, "value outside 0..65535");
    v[k] = static_cast<int>(*n);
  }
  if (v[2] <= 0 || v[3] <= 0) return f.error(path, "width and height must be > 0");
  return Rect{v[0], v[1], v[2], v[3]};
}

}  // namespace

Result<TruthFile> parse_truth_json(std::string_view text, const char* name) {
  auto parsed = JsonFile::parse(std::string(text), name);
  if (!parsed) return parsed.error();
  const JsonFile& f = *parsed;
  TruthFile t;
  auto roi = f.member(0, "roi", "roi");
  if (!roi) return roi.error();
  auto r = read_rect(f, *roi, "roi");
  if (!r) return r.error();
  t.roi = *r;

  auto planes = f.member(0, "planes", "planes");
  if (!planes) return planes.error();
  auto c = f.integer(*planes, "planes");
  if (!c) return c.error();

  auto facets = f.member(0, "facets", "facets");
  if (!facets) return facets.error();
  PETRA_TRY(f.array(*facets, "facets"));
  const auto list = f.elements(*facets);
  for (std::size_t k = 0; k < list.size(); ++k) {
    const std::string p = "facets[" + std::to_string(k) + "]";
    PETRA_TRY(f.object(list[k], p));
    TruthFacet facet;
    auto n = f.member(list[k], "normal", p + ".normal");
    if (!n) return n.error();
    auto nv = f.unit_vec3(*n, p + ".normal");
    if (!nv) return nv.error();
    facet.normal = *nv;
    auto cm = f.member(list[k], "centroid_mm", p + ".centroid_mm");
    if (!cm) return cm.error();
    auto cv = f.vec3(*cm, p + ".centroid_mm");
    if (!cv) return cv.error();
    facet.centroid_mm = *cv;
    auto poly = f.member(list[k], "polygon_mm", p + ".polygon_mm");
    if (!poly) return poly.error();
    PETRA_TRY(f.array(*poly, p + ".polygon_mm"));
    const auto verts = f.elements(*poly);
    if (verts.size() < 3) return f.error(p + ".polygon_mm", "needs at least 3 vertices");
    for (std::size_t v = 0; v < verts.size(); ++v) {
      auto pv = f.vec3(verts[v], p + ".polygon_mm[" + std::to_string(v) + "]");
      if (!pv) return pv.error();
      facet.polygon_mm.push_back(*pv);
    }
    auto area = f.member(list[k], "visible_area_mm2", p + ".visible_area_mm2");
    if (!area) return area.error();
    auto av = f.number(*area, p + ".visible_area_mm2");
    if (!av) return av.error();
    if (*av < 0) return f.error(p + ".visible_area_mm2", "must be >= 0");
    facet.visible_area_mm2 = *av;
    if (const std::uint32_t g = f.optional_member(list[k], "grind_face")) {
      auto gv = f.boolean(g, p + ".grind_face");
      if (!gv) return gv.error();
      facet.grind_face = *gv;
    }
    if (const std::uint32_t fl = f.optional_member(list[k], "flatness_rms_mm")) {
      auto fv = f.number(fl, p + ".flatness_rms_mm");
      if (!fv) return fv.error();
      if (*fv < 0) return f.error(p + ".flatness_rms_mm", "must be >= 0");
      facet.flatness_rms_mm = *fv;
    }
    t.facets.push_back(std::move(facet));
  }
  if (*c < 1 || *c > static_cast<long long>(t.facets.size()))
    return Error::make(Errc::out_of_range, "%s: planes = %lld: must be 1..%zu (the facets listed)",
                       name, *c, t.facets.size());
  t.planes = static_cast<int>(*c);

  auto ground = f.member(0, "ground", "ground");
  if (!ground) return ground.error();
  PETRA_TRY(f.object(*ground, "ground"));
  auto gn = f.member(*ground, "normal", "ground.normal");
  if (!gn) return gn.error();
  auto gnv = f.unit_vec3(*gn, "ground.normal");
  if (!gnv) return gnv.error();
  t.ground_normal = *gnv;
  auto gd = f.member(*ground, "d_mm", "ground.d_mm");
  if (!gd) return gd.error();
  auto gdv = f.number(*gd, "ground.d_mm");
  if (!gdv) return gdv.error();
  t.ground_d_mm = *gdv;

  auto sun = f.member(0, "sun_dir", "sun_dir");
  if (!sun) return sun.error();
  auto sv = f.unit_vec3(*sun, "sun_dir");
  if (!sv) return sv.error();
  t.sun_dir = *sv;
  auto seed = f.member(0, "seed", "seed");
  if (!seed) return seed.error();
  auto seedv = f.integer(*seed, "seed");
  if (!seedv) return seedv.error();
  t.seed = *seedv;

  if (const std::uint32_t rr = f.optional_member(0, "roi_rectified")) {
    auto rv = read_rect(f, rr, "roi_rectified");
    if (!rv) return rv.error();
    t.roi_rectified = *rv;
  }
  return t;
}

}  // namespace petra::sim
