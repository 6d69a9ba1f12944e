#include "sim/ground/command_builder.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <type_traits>

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

}  // namespace

std::string command_usage() {
  std::ostringstream o;
  for (const cmd::CommandDesc& c : cmd::command_table()) {
    o << "  " << c.name;
    for (const auto& f : c.fields)
      o << " " << f.name << "=<" << f.min << ".." << f.max
        << (f.unit[0] ? std::string(" ") + f.unit : "") << ">";
    o << "\n      " << c.description << "\n";
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
  if (auto* roi = std::get_if<cmd::SelectRoiArgs>(&c.args); roi != nullptr && click)
    roi->has_click = 1;
  return c;
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
  if (!out) return Error::make(Errc::io_error, "counter file %s: cannot write", path.c_str());
  return next;
}

}  // namespace petra::ground
