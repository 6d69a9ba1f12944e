#include "fsw/param_table.hpp"

#include <memory>
#include <string_view>

#include "algo/core/json_reader.hpp"

namespace petra::fsw {

namespace {
std::size_t index_of(std::uint16_t id) {
  for (std::size_t i = 0; i < kParamCount; ++i)
    if (kParamTable[i].id == id) return i;
  return kParamCount;
}
}  // namespace

ParamTable::ParamTable() {
  for (std::size_t i = 0; i < kParamCount; ++i) values_[i] = kParamTable[i].default_value;
}

double ParamTable::get(ParamId id) const {
  const std::size_t i = index_of(static_cast<std::uint16_t>(id));
  return i < kParamCount ? values_[i] : 0.0;
}

bool ParamTable::get(std::uint16_t id, double& value) const {
  const std::size_t i = index_of(id);
  if (i == kParamCount) return false;
  value = values_[i];
  return true;
}

Status ParamTable::set(std::uint16_t id, double value) {
  const std::size_t i = index_of(id);
  if (i == kParamCount) return Error::make(Errc::invalid_argument, "parameter %u: unknown", id);
  const ParamDesc& p = kParamTable[i];
  if (!param_value_valid(p, value))
    return Error::make(Errc::out_of_range, "parameter %s = %g: outside %g..%g%s", p.name, value,
                       p.min, p.max, p.integer ? " (whole numbers)" : "");
  values_[i] = value;
  return {};
}

Result<int> ParamTable::load_defaults(const char* text, std::size_t size) {
  constexpr std::size_t kTokens = 512;
  auto tokens = std::make_unique<json::Token[]>(kTokens);  // init only
  auto doc = json::Document::parse(std::string_view(text, size), std::span(tokens.get(), kTokens));
  if (!doc) return Error::make(Errc::parse_error, "parameters: %s", doc.error().message);
  if (doc->token(0).type != json::Type::object)
    return Error::make(Errc::wrong_type, "parameters: top level must be an object");
  int set_count = 0;
  // Members are key, value pairs after the root; walk them by subtree skips.
  std::uint32_t t = 1;
  for (std::uint32_t m = 0; m < doc->token(0).count; ++m) {
    const std::string_view key = doc->text_of(t);
    const std::uint32_t value = t + 1;
    const ParamDesc* p = nullptr;
    for (const ParamDesc& d : kParamTable)
      if (key == d.name) p = &d;
    if (p == nullptr)
      return Error::make(Errc::invalid_argument, "parameters: '%.*s' is not a parameter",
                         static_cast<int>(key.size()), key.data());
    if (doc->token(value).type != json::Type::number)
      return Error::make(Errc::wrong_type, "parameters: %s: expected a number", p->name);
    PETRA_TRY(set(p->id, doc->token(value).number));
    ++set_count;
    t = doc->token(value).next;
  }
  return set_count;
}

}  // namespace petra::fsw
