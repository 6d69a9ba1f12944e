#include "sim/arm/planes_file.hpp"

#include <cmath>

#include "algo/core/json_reader.hpp"

namespace petra::sim {

namespace {

Result<Eigen::Vector3d> vec3(const json::Document& doc, std::uint32_t obj, const char* key,
                             const char* where) {
  const std::uint32_t arr = doc.find(obj, key);
  if (arr == 0) return Error::make(Errc::missing_field, "%s.%s: missing", where, key);
  if (doc.token(arr).type != json::Type::array || doc.token(arr).count != 3) {
    return Error::make(Errc::wrong_type, "%s.%s: expected an array of 3 numbers", where, key);
  }
  Eigen::Vector3d v;
  for (std::uint32_t k = 0; k < 3; ++k) {
    const json::Token& t = doc.token(doc.element(arr, k));
    if (t.type != json::Type::number || !std::isfinite(t.number)) {
      return Error::make(Errc::wrong_type, "%s.%s[%u]: not a number", where, key, k);
    }
    v[k] = t.number;
  }
  return v;
}

Result<Eigen::Vector3d> unit(const json::Document& doc, std::uint32_t obj, const char* key,
                             const char* where) {
  auto v = vec3(doc, obj, key, where);
  if (!v) return v.error();
  if (std::abs(v->norm() - 1.0) > 1e-3) {
    return Error::make(Errc::invalid_argument, "%s.%s: not a unit vector (|n| = %.6f)", where, key,
                       v->norm());
  }
  return v->normalized();
}

double optional_number(const json::Document& doc, std::uint32_t obj, const char* key) {
  const std::uint32_t i = doc.find(obj, key);
  return (i != 0 && doc.token(i).type == json::Type::number) ? doc.token(i).number : 0.0;
}

}  // namespace

Result<PlanesFile> parse_planes_json(std::string_view text) {
  std::vector<json::Token> tokens(4096 + text.size() / 4);
  auto doc = json::Document::parse(text, tokens);
  if (!doc) return doc.error();
  if (doc->token(0).type != json::Type::object)
    return Error::make(Errc::wrong_type, "planes.json: not an object");
  const std::uint32_t arr = doc->find(0, "planes");
  if (arr == 0) return Error::make(Errc::missing_field, "planes: missing");
  if (doc->token(arr).type != json::Type::array)
    return Error::make(Errc::wrong_type, "planes: expected an array");
  PlanesFile out;
  char where[32];
  for (std::uint32_t k = 0; k < doc->token(arr).count; ++k) {
    const std::uint32_t p = doc->element(arr, k);
    std::snprintf(where, sizeof where, "planes[%u]", k);
    if (doc->token(p).type != json::Type::object)
      return Error::make(Errc::wrong_type, "%s: expected an object", where);
    GrindPlane g;
    auto n = unit(*doc, p, "normal", where);
    if (!n) return n.error();
    auto c = vec3(*doc, p, "centroid_mm", where);
    if (!c) return c.error();
    g.normal = *n;
    g.centroid_mm = *c;
    g.area_mm2 = optional_number(*doc, p, "area_mm2");
    g.rms_mm = optional_number(*doc, p, "rms_mm");
    out.planes.push_back(g);
  }
  const std::uint32_t ground = doc->find(0, "ground");
  if (ground != 0 && doc->token(ground).type == json::Type::object) {
    auto n = unit(*doc, ground, "normal", "ground");
    if (!n) return n.error();
    const std::uint32_t d = doc->find(ground, "d_mm");
    if (d == 0 || doc->token(d).type != json::Type::number) {
      return Error::make(Errc::missing_field, "ground.d_mm: missing or not a number");
    }
    out.ground = Eigen::Vector4d(n->x(), n->y(), n->z(), doc->token(d).number);
  }
  return out;
}

}  // namespace petra::sim
