#include "sim/score/json_fields.hpp"

#include <cmath>
#include <utility>

namespace petra::sim {

Result<JsonFile> JsonFile::parse(std::string text, std::string name) {
  JsonFile f;
  f.text_ = std::move(text);
  f.name_ = std::move(name);
  // Every token takes at least two characters of text, separators included.
  f.tokens_.resize(f.text_.size() / 2 + 16);
  auto doc = json::Document::parse(f.text_, f.tokens_);
  if (!doc) return Error::make(doc.error().code, "%s: %s", f.name_.c_str(), doc.error().message);
  f.doc_ = *doc;
  if (f.doc_.token(0).type != json::Type::object)
    return Error::make(Errc::wrong_type, "%s: expected a JSON object", f.name_.c_str());
  return f;
}

JsonFile::JsonFile(JsonFile&& other) noexcept
    : text_(std::move(other.text_)),
      name_(std::move(other.name_)),
      tokens_(std::move(other.tokens_)) {
  // The document points into the text and tokens: parse again over the
  // moved storage (cannot fail: it parsed before).
  auto doc = json::Document::parse(text_, tokens_);
  if (doc) doc_ = *doc;
}

Error JsonFile::error(const std::string& path, const char* what) const {
  return Error::make(Errc::parse_error, "%s: %s: %s", name_.c_str(), path.c_str(), what);
}

Result<std::uint32_t> JsonFile::member(std::uint32_t obj, std::string_view key,
                                       const std::string& path) const {
  const std::uint32_t i = doc_.find(obj, key);
  if (i == 0)
    return Error::make(Errc::missing_field, "%s: %s: missing", name_.c_str(), path.c_str());
  return i;
}

std::uint32_t JsonFile::optional_member(std::uint32_t obj, std::string_view key) const {
  return doc_.find(obj, key);
}

Result<std::uint32_t> JsonFile::object(std::uint32_t i, const std::string& path) const {
  if (doc_.token(i).type != json::Type::object) return error(path, "expected an object");
  return i;
}

Result<std::uint32_t> JsonFile::array(std::uint32_t i, const std::string& path) const {
  if (doc_.token(i).type != json::Type::array) return error(path, "expected an array");
  return i;
}

Result<double> JsonFile::number(std::uint32_t i, const std::string& path) const {
  if (doc_.token(i).type != json::Type::number) return error(path, "expected a number");
  return doc_.token(i).number;
}

Result<long long> JsonFile::integer(std::uint32_t i, const std::string& path) const {
  auto v = number(i, path);
  if (!v) return v.error();
  if (*v != std::floor(*v) || std::abs(*v) > 9007199254740991.0)
    return error(path, "expected a whole number");
  return static_cast<long long>(*v);
}

Result<bool> JsonFile::boolean(std::uint32_t i, const std::string& path) const {
  if (doc_.token(i).type != json::Type::boolean) return error(path, "expected true or false");
  return doc_.token(i).number != 0.0;
}

Result<std::string> JsonFile::string(std::uint32_t i, const std::string& path) const {
  if (doc_.token(i).type != json::Type::string) return error(path, "expected a string");
  return std::string(doc_.text_of(i));
}

Result<Eigen::Vector3d> JsonFile::vec3(std::uint32_t i, const std::string& path) const {
  const json::Token& t = doc_.token(i);
  if (t.type != json::Type::array || t.count != 3)
    return error(path, "expected an array of 3 numbers");
  Eigen::Vector3d v;
  std::uint32_t e = i + 1;
  for (int k = 0; k < 3; ++k) {
    if (doc_.token(e).type != json::Type::number)
      return error(path, "expected an array of 3 numbers");
    v[k] = doc_.token(e).number;
    e = doc_.token(e).next;
  }
  return v;
}

// Within this of 1, a vector's norm is a unit vector's as rounded to doubles.
constexpr double kUnitAsWritten = 1e-14;

Result<Eigen::Vector3d> JsonFile::unit_vec3(std::uint32_t i, const std::string& path) const {
  auto v = vec3(i, path);
  if (!v) return v.error();
  const double n = v->norm();
  if (!(std::abs(n - 1.0) <= 1e-3)) {
    char what[80];
    std::snprintf(what, sizeof what, "length %.6g, expected a unit vector", n);
    return error(path, what);
  }
  // A unit vector written with 17 digits reads back as itself; dividing it by
  // its norm (1 within rounding) would move its last bits.
  if (std::abs(n - 1.0) <= kUnitAsWritten) return *v;
  return Eigen::Vector3d(*v / n);
}

std::vector<std::uint32_t> JsonFile::elements(std::uint32_t arr) const {
  std::vector<std::uint32_t> out;
  const json::Token& t = doc_.token(arr);
  if (t.type != json::Type::array) return out;
  std::uint32_t e = arr + 1;
  for (std::uint32_t k = 0; k < t.count; ++k) {
    out.push_back(e);
    e = doc_.token(e).next;
  }
  return out;
}

}  // namespace petra::sim
