#include "algo/camera/calib_json.hpp"

#include <array>
#include <cmath>

#include "algo/core/json_reader.hpp"
#include "algo/core/json_writer.hpp"

namespace petra {

namespace {

constexpr std::size_t kMaxTokens = 256;

class CameraReader {
 public:
  CameraReader(const json::Document& doc, std::uint32_t obj, const char* name)
      : doc_(doc), obj_(obj), name_(name) {}

  Result<double> number(const char* key) const {
    const std::uint32_t i = doc_.find(obj_, key);
    if (i == 0) return Error::make(Errc::missing_field, "%s.%s: missing", name_, key);
    if (doc_.token(i).type != json::Type::number)
      return Error::make(Errc::wrong_type, "%s.%s: expected a number, got %s", name_, key,
                         json::type_name(doc_.token(i).type));
    return doc_.token(i).number;
  }

  Result<int> integer(const char* key) const {
    auto v = number(key);
    if (!v) return v.error();
    if (*v != std::floor(*v) || *v < 1 || *v > 65535)
      return Error::make(Errc::invalid_argument, "%s.%s: expected a whole number 1..65535, got %g",
                         name_, key, *v);
    return static_cast<int>(*v);
  }

  template <std::size_t N>
  Result<std::array<double, N>> numbers(const char* key) const {
    const std::uint32_t arr = doc_.find(obj_, key);
    if (arr == 0) return Error::make(Errc::missing_field, "%s.%s: missing", name_, key);
    if (doc_.token(arr).type != json::Type::array || doc_.token(arr).count != N)
      return Error::make(Errc::wrong_type, "%s.%s: expected an array of %zu numbers", name_, key,
                         N);
    std::array<double, N> out{};
    for (std::uint32_t k = 0; k < N; ++k) {
      const std::uint32_t e = doc_.element(arr, k);
      if (doc_.token(e).type != json::Type::number)
        return Error::make(Errc::wrong_type, "%s.%s[%u]: expected a number", name_, key, k);
      out[k] = doc_.token(e).number;
    }
    return out;
  }

 private:
  const json::Document& doc_;
  std::uint32_t obj_;
  const char* name_;
};

Result<TsaiCamera> read_camera(const json::Document& doc, const char* name) {
  const std::uint32_t obj = doc.find(0, name);
  if (obj == 0) return Error::make(Errc::missing_field, "%s: missing", name);
  if (doc.token(obj).type != json::Type::object)
    return Error::make(Errc::wrong_type, "%s: expected an object", name);
  CameraReader r(doc, obj, name);
  TsaiCamera c;
  auto width = r.integer("width");
  if (!width) return width.error();
  auto height = r.integer("height");
  if (!height) return height.error();
  c.width = *width;
  c.height = *height;
  struct Field {
    const char* key;
    double* dst;
  };
  const Field fields[] = {{"f", &c.f_mm},   {"kappa1", &c.kappa1}, {"sx", &c.sx},
                          {"cx", &c.cx_px}, {"cy", &c.cy_px},      {"dx", &c.dx_mm},
                          {"dy", &c.dy_mm}};
  for (const Field& f : fields) {
    auto v = r.number(f.key);
    if (!v) return v.error();
    *f.dst = *v;
  }
  auto R = r.numbers<9>("R");
  if (!R) return R.error();
  auto T = r.numbers<3>("T");
  if (!T) return T.error();
  std::size_t k = 0;  // R is row-major
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) c.R(i, j) = (*R)[k++];
    c.T_mm(i) = (*T)[static_cast<std::size_t>(i)];
  }
  PETRA_TRY(validate(c, name));
  return c;
}

Status expect_string(const json::Document& doc, const char* key, std::string_view want) {
  const std::uint32_t i = doc.find(0, key);
  if (i == 0) return Error::make(Errc::missing_field, "%s: missing", key);
  if (doc.token(i).type != json::Type::string)
    return Error::make(Errc::wrong_type, "%s: expected a string", key);
  if (doc.text_of(i) != want)
    return Error::make(Errc::invalid_argument, "%s: expected \"%.*s\"", key,
                       static_cast<int>(want.size()), want.data());
  return {};
}

void write_camera(json::Writer& w, const char* name, const TsaiCamera& c) {
  w.key(name).begin_object();
  w.key("width").integer(c.width).key("height").integer(c.height);
  w.key("f").number(c.f_mm).key("kappa1").number(c.kappa1).key("sx").number(c.sx);
  w.key("cx").number(c.cx_px).key("cy").number(c.cy_px);
  w.key("dx").number(c.dx_mm).key("dy").number(c.dy_mm);
  w.key("R").begin_array();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) w.number(c.R(i, j));
  w.end_array();
  w.key("T").begin_array();
  for (int i = 0; i < 3; ++i) w.number(c.T_mm(i));
  w.end_array();
  w.end_object();
}

}  // namespace

Result<StereoRig> parse_calib_json(std::string_view text) {
  std::array<json::Token, kMaxTokens> tokens;
  auto doc = json::Document::parse(text, tokens);
  if (!doc) return doc.error();
  if (doc->token(0).type != json::Type::object)
    return Error::make(Errc::wrong_type, "calib: top level must be an object");
  PETRA_TRY(expect_string(*doc, "model", "tsai-rac"));
  PETRA_TRY(expect_string(*doc, "units", "mm"));
  StereoRig rig;
  auto left = read_camera(*doc, "left");
  if (!left) return left.error();
  auto right = read_camera(*doc, "right");
  if (!right) return right.error();
  rig.left = *left;
  rig.right = *right;
  return rig;
}

Result<std::size_t> format_calib_json(const StereoRig& rig, std::span<char> out) {
  json::Writer w(out);
  w.begin_object().key("model").string("tsai-rac").key("units").string("mm");
  write_camera(w, "left", rig.left);
  write_camera(w, "right", rig.right);
  w.end_object().raw("\n");
  return w.finish();
}

}  // namespace petra
