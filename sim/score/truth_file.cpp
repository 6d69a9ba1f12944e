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

// One facet object at token i ("facets[k]" at path p).
Result<TruthFacet> read_facet(const JsonFile& f, std::uint32_t i, const std::string& p) {
  TruthFacet facet;
  auto n = f.member(i, "normal", p + ".normal");
  if (!n) return n.error();
  auto nv = f.unit_vec3(*n, p + ".normal");
  if (!nv) return nv.error();
  facet.normal = *nv;
  auto cm = f.member(i, "centroid_mm", p + ".centroid_mm");
  if (!cm) return cm.error();
  auto cv = f.vec3(*cm, p + ".centroid_mm");
  if (!cv) return cv.error();
  facet.centroid_mm = *cv;
  auto poly = f.member(i, "polygon_mm", p + ".polygon_mm");
  if (!poly) return poly.error();
  PETRA_TRY(f.array(*poly, p + ".polygon_mm"));
  const auto verts = f.elements(*poly);
  if (verts.size() < 3) return f.error(p + ".polygon_mm", "needs at least 3 vertices");
  for (std::size_t v = 0; v < verts.size(); ++v) {
    auto pv = f.vec3(verts[v], p + ".polygon_mm[" + std::to_string(v) + "]");
    if (!pv) return pv.error();
    facet.polygon_mm.push_back(*pv);
  }
  auto area = f.member(i, "visible_area_mm2", p + ".visible_area_mm2");
  if (!area) return area.error();
  auto av = f.number(*area, p + ".visible_area_mm2");
  if (!av) return av.error();
  if (*av < 0) return f.error(p + ".visible_area_mm2", "must be >= 0");
  facet.visible_area_mm2 = *av;
  if (const std::uint32_t g = f.optional_member(i, "grind_face")) {
    auto gv = f.boolean(g, p + ".grind_face");
    if (!gv) return gv.error();
    facet.grind_face = *gv;
  }
  if (const std::uint32_t fl = f.optional_member(i, "flatness_rms_mm")) {
    auto fv = f.number(fl, p + ".flatness_rms_mm");
    if (!fv) return fv.error();
    if (*fv < 0) return f.error(p + ".flatness_rms_mm", "must be >= 0");
    facet.flatness_rms_mm = *fv;
  }
  return facet;
}

// A multi-rock facet's judgement (all four fields required).
Status read_judgement(const JsonFile& f, std::uint32_t i, const std::string& p, TruthFacet& out) {
  auto g = f.member(i, "grindable", p + ".grindable");
  if (!g) return g.error();
  auto gv = f.boolean(*g, p + ".grindable");
  if (!gv) return gv.error();
  out.grindable = *gv;
  auto r = f.member(i, "reachable", p + ".reachable");
  if (!r) return r.error();
  auto rv = f.boolean(*r, p + ".reachable");
  if (!rv) return rv.error();
  out.reachable = *rv;
  auto why = f.member(i, "reason", p + ".reason");
  if (!why) return why.error();
  auto wv = f.string(*why, p + ".reason");
  if (!wv) return wv.error();
  out.reason = *wv;
  auto rr = f.member(i, "reach_reason", p + ".reach_reason");
  if (!rr) return rr.error();
  auto rrv = f.string(*rr, p + ".reach_reason");
  if (!rrv) return rrv.error();
  out.reach_reason = *rrv;
  return {};
}

Result<TruthRock> read_rock(const JsonFile& f, std::uint32_t i, const std::string& p) {
  PETRA_TRY(f.object(i, p));
  TruthRock rock;
  auto id = f.member(i, "id", p + ".id");
  if (!id) return id.error();
  auto idv = f.integer(*id, p + ".id");
  if (!idv) return idv.error();
  rock.id = static_cast<int>(*idv);
  auto roi = f.member(i, "roi", p + ".roi");
  if (!roi) return roi.error();
  auto rv = read_rect(f, *roi, p + ".roi");
  if (!rv) return rv.error();
  rock.roi = *rv;
  if (const std::uint32_t c = f.optional_member(i, "click")) {
    const auto uv = f.elements(c);
    if (uv.size() != 2) return f.error(p + ".click", "expected [u, v]");
    auto u = f.integer(uv[0], p + ".click");
    auto v = f.integer(uv[1], p + ".click");
    if (!u || !v) return f.error(p + ".click", "expected [u, v]");
    rock.click = Eigen::Vector2i(static_cast<int>(*u), static_cast<int>(*v));
  }
  for (const char* key : {"height_mm", "size_mm"}) {
    auto m = f.member(i, key, p + "." + key);
    if (!m) return m.error();
    auto mv = f.number(*m, p + "." + key);
    if (!mv) return mv.error();
    (std::string_view(key) == "height_mm" ? rock.height_mm : rock.size_mm) = *mv;
  }
  auto facets = f.member(i, "facets", p + ".facets");
  if (!facets) return facets.error();
  PETRA_TRY(f.array(*facets, p + ".facets"));
  const auto list = f.elements(*facets);
  for (std::size_t k = 0; k < list.size(); ++k) {
    const std::string fp = p + ".facets[" + std::to_string(k) + "]";
    PETRA_TRY(f.object(list[k], fp));
    auto facet = read_facet(f, list[k], fp);
    if (!facet) return facet.error();
    PETRA_TRY(read_judgement(f, list[k], fp, *facet));
    rock.facets.push_back(std::move(*facet));
  }
  return rock;
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
    auto facet = read_facet(f, list[k], p);
    if (!facet) return facet.error();
    t.facets.push_back(std::move(*facet));
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
  if (const std::uint32_t rocks = f.optional_member(0, "rocks")) {
    PETRA_TRY(f.array(rocks, "rocks"));
    const auto items = f.elements(rocks);
    for (std::size_t k = 0; k < items.size(); ++k) {
      auto rock = read_rock(f, items[k], "rocks[" + std::to_string(k) + "]");
      if (!rock) return rock.error();
      t.rocks.push_back(std::move(*rock));
    }
  }
  return t;
}

}  // namespace petra::sim
