#include "sim/score/planes_file.hpp"

#include <string>

#include "sim/score/json_fields.hpp"

namespace petra::sim {

namespace {

// An optional number member: absent is fine, present must be a number.
Status optional_number(const JsonFile& f, std::uint32_t obj, const char* key,
                       const std::string& path, double& out) {
  if (const std::uint32_t i = f.optional_member(obj, key)) {
    auto v = f.number(i, path);
    if (!v) return v.error();
    out = *v;
  }
  return {};
}

}  // namespace

Result<PlanesFile> parse_planes_json(std::string_view text, const char* name) {
  auto parsed = JsonFile::parse(std::string(text), name);
  if (!parsed) return parsed.error();
  const JsonFile& f = *parsed;
  PlanesFile out;
  auto planes = f.member(0, "planes", "planes");
  if (!planes) return planes.error();
  PETRA_TRY(f.array(*planes, "planes"));
  const auto list = f.elements(*planes);
  for (std::size_t k = 0; k < list.size(); ++k) {
    const std::string p = "planes[" + std::to_string(k) + "]";
    PETRA_TRY(f.object(list[k], p));
    OutputPlane plane;
    auto n = f.member(list[k], "normal", p + ".normal");
    if (!n) return n.error();
    auto nv = f.unit_vec3(*n, p + ".normal");
    if (!nv) return nv.error();
    plane.normal = *nv;
    auto c = f.member(list[k], "centroid_mm", p + ".centroid_mm");
    if (!c) return c.error();
    auto cv = f.vec3(*c, p + ".centroid_mm");
    if (!cv) return cv.error();
    plane.centroid_mm = *cv;
    if (const std::uint32_t g = f.optional_member(list[k], "grind_point_mm")) {
      auto gv = f.vec3(g, p + ".grind_point_mm");
      if (!gv) return gv.error();
      plane.grind_point_mm = *gv;
    }
    PETRA_TRY(optional_number(f, list[k], "area_mm2", p + ".area_mm2", plane.area_mm2));
    PETRA_TRY(optional_number(f, list[k], "rms_mm", p + ".rms_mm", plane.rms_mm));
    if (const std::uint32_t t = f.optional_member(list[k], "triangles")) {
      auto tv = f.integer(t, p + ".triangles");
      if (!tv) return tv.error();
      plane.triangles = *tv;
    }
    out.planes.push_back(plane);
  }
  if (const std::uint32_t g = f.optional_member(0, "ground")) {
    PETRA_TRY(f.object(g, "ground"));
    auto gn = f.member(g, "normal", "ground.normal");
    if (!gn) return gn.error();
    auto gnv = f.unit_vec3(*gn, "ground.normal");
    if (!gnv) return gnv.error();
    auto gd = f.member(g, "d_mm", "ground.d_mm");
    if (!gd) return gd.error();
    auto gdv = f.number(*gd, "ground.d_mm");
    if (!gdv) return gdv.error();
    out.ground = GroundPlane{*gnv, *gdv};
  }
  return out;
}

}  // namespace petra::sim
