#include "sim/ground/command_builder.hpp"

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string_view>
#include <type_traits>

#include "cmd/param_defs.hpp"

namespace petra::ground {

namespace {

bool parse_number(const std::string& s, double& v) {
  char* end = nullptr;
  v = std::strtod(s.c_str(), &end);
  return !s.empty() && end != nullptr && *end == '\0' && std::isfinite(v);
}

template <class T>
void assign(T& slot, double v) {
  slot = static_cast<T>(v);
}

// The only fields an operator may leave out: SELECT_ROI's click (none by
// default); has_click follows from the click fields when not given.
bool optional_field(const cmd::CommandDesc& c, const wire::FieldDesc& f) {
  const std::string_view n = f.name;
  return c.code == static_cast<std::uint8_t>(cmd::FunctionCode::SELECT_ROI) &&
         (n == "has_click" || n == "click_u_px" || n == "click_v_px");
}

// Checks between fields that the ground can make before sending (the
// onboard validator makes them again, with the image size).
Status check_consistency(const cmd::Command& c, const std::vector<std::string>& given) {
  auto has = [&](const char* f) { return std::find(given.begin(), given.end(), f) != given.end(); };
  if (const auto* roi = std::get_if<cmd::SelectRoiArgs>(&c.args)) {
    if (has("click_u_px") != has("click_v_px"))
      return Error::make(Errc::missing_field,
                         "SELECT_ROI: give both click_u_px and click_v_px, or neither");
    if (roi->has_click != 0 && !has("click_u_px"))
      return Error::make(Errc::missing_field,
                         "SELECT_ROI: has_click=1 needs click_u_px and click_v_px");
    if (roi->has_click != 0 &&
        (roi->click_u_px < roi->x_px || roi->click_u_px >= roi->x_px + roi->w_px ||
         roi->click_v_px < roi->y_px || roi->click_v_px >= roi->y_px + roi->h_px))
      return Error::make(Errc::out_of_range,
                         "SELECT_ROI: click_u_px, click_v_px = %u, %u lies outside the ROI",
                         roi->click_u_px, roi->click_v_px);
  } else if (const auto* set = std::get_if<cmd::SetParamArgs>(&c.args)) {
    const ParamDesc* p = find_param(set->param_id);
    if (p == nullptr)
      return Error::make(Errc::invalid_argument, "SET_PARAM.param_id = %u: no such parameter",
                         set->param_id);
    if (!param_value_valid(*p, set->value))
      return Error::make(Errc::out_of_range, "SET_PARAM.value = %g: outside %s's range %g..%g",
                         set->value, p->name, p->min, p->max);
  } else if (const auto* get = std::get_if<cmd::GetParamArgs>(&c.args)) {
    if (find_param(get->param_id) == nullptr)
      return Error::make(Errc::invalid_argument, "GET_PARAM.param_id = %u: no such parameter",
                         get->param_id);
  }
  return {};
}

}  // namespace

std::string command_usage() {
  std::ostringstream o;
  for (const cmd::CommandDesc& c : cmd::command_table()) {
    o << "  " << c.name;
    bool optional = false;
    for (const auto& f : c.fields) {
      const bool opt = optional_field(c, f);
      optional = optional || opt;
      o << " " << (opt ? "[" : "") << f.name << "=<" << f.min << ".." << f.max
        << (f.unit[0] ? std::string(" ") + f.unit : "") << ">" << (opt ? "]" : "");
    }
    o << "\n      " << c.description << "\n";
    if (optional) o << "      [optional]: default no click; has_click=1 when the click is given\n";
  }
  return o.str();
}

Result<cmd::Command> build_command(const std::string& name, const std::vector<std::string>& words) {
  std::string upper = name;
  std::transform(upper.begin(), upper.end(), upper.begin(),
                 [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
  const cmd::CommandDesc* desc = cmd::find_command(upper);
  if (desc == nullptr)
    return Error::make(Errc::invalid_argument, "unknown command '%s' (see petra cmd --help)",
                       name.c_str());
  cmd::Command c;
  c.code = static_cast<cmd::FunctionCode>(desc->code);
  c.args = cmd::default_args(c.code);
  bool click = false;
  std::vector<std::string> given;
  for (const std::string& w : words) {
    const auto eq = w.find('=');
    if (eq == std::string::npos)
      return Error::make(Errc::invalid_argument, "%s: '%s' is not field=value", desc->name,
                         w.c_str());
    const std::string key = w.substr(0, eq);
    const std::string value = w.substr(eq + 1);
    const wire::FieldDesc* f = nullptr;
    for (const auto& fd : desc->fields)
      if (key == fd.name) f = &fd;
    if (f == nullptr)
      return Error::make(Errc::invalid_argument, "%s has no field '%s'", desc->name, key.c_str());
    if (std::find(given.begin(), given.end(), key) != given.end())
      return Error::make(Errc::invalid_argument, "%s.%s: given twice", desc->name, f->name);
    given.push_back(key);
    double v = 0;
    if (!parse_number(value, v))
      return Error::make(Errc::invalid_argument, "%s.%s: '%s' is not a number", desc->name, f->name,
                         value.c_str());
    const bool integral = f->type != wire::FieldType::f32 && f->type != wire::FieldType::f64;
    if (v < f->min || v > f->max || (integral && std::floor(v) != v))
      return Error::make(Errc::out_of_range, "%s.%s = %s: outside %g..%g%s", desc->name, f->name,
                         value.c_str(), f->min, f->max, integral ? " (whole numbers)" : "");
    if (key == "click_u_px" || key == "click_v_px") click = true;
    std::visit(
        [&](auto& args) {
          if constexpr (!std::is_same_v<std::decay_t<decltype(args)>, std::monostate>) {
            args.each([&](const char* field, auto& member) {
              if (key != field) return;
              if constexpr (std::is_arithmetic_v<std::decay_t<decltype(member)>>) assign(member, v);
            });
          }
        },
        c.args);
  }
  std::string missing;
  for (const auto& f : desc->fields)
    if (!optional_field(*desc, f) && std::find(given.begin(), given.end(), f.name) == given.end())
      missing += (missing.empty() ? "" : ", ") + std::string(f.name);
  if (!missing.empty())
    return Error::make(Errc::missing_field, "%s: missing %s (every field is required)", desc->name,
                       missing.c_str());
  if (auto* roi = std::get_if<cmd::SelectRoiArgs>(&c.args); roi != nullptr && click)
    roi->has_click = 1;
  PETRA_TRY(check_consistency(c, given));
  return c;
}

Result<cmd::AuthKey> load_uplink_key(const std::string& path) {
  // cmd::load_key_file says "cannot open" only: the ground names the reason.
  if (::access(path.c_str(), R_OK) != 0)
    return Error::make(Errc::io_error, "key file %s: %s", path.c_str(), std::strerror(errno));
  if (std::filesystem::is_directory(path))
    return Error::make(Errc::io_error, "key file %s: is a directory, not a file", path.c_str());
  return cmd::load_key_file(path.c_str());
}

Result<std::uint32_t> next_counter(const std::string& path) {
  std::uint64_t last = 0;
  {
    std::ifstream in(path);
    if (in && !(in >> last))
      return Error::make(Errc::parse_error, "counter file %s: not a number", path.c_str());
  }
  if (last >= 0xFFFFFFFFull)
    return Error::make(Errc::capacity_exceeded,
                       "counter file %s: counter exhausted; new key needed", path.c_str());
  const auto next = static_cast<std::uint32_t>(last + 1);
  std::ofstream out(path, std::ios::trunc);
  out << next << "\n";
  if (!out)
    return Error::make(Errc::io_error, "counter file %s: %s", path.c_str(), std::strerror(errno));
  return next;
}

}  // namespace petra::ground
