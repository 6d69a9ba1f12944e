#include "sim/gnd/command_request.hpp"

#include <cstdio>
#include <string>
#include <vector>

#include "algo/core/json_reader.hpp"
#include "sim/ground/command_builder.hpp"

namespace petra::gnd {

Result<cmd::Command> parse_command_request(std::string_view body) {
  if (body.size() > kMaxRequestBytes)
    return Error::make(Errc::invalid_argument, "request: body of %zu bytes exceeds %zu",
                       body.size(), kMaxRequestBytes);
  std::vector<json::Token> tokens(256);
  auto doc = json::Document::parse(body, tokens);
  if (!doc) return Error::make(Errc::parse_error, "request: not JSON: %s", doc.error().message);
  if (doc->token(0).type != json::Type::object)
    return Error::make(Errc::invalid_argument, "request: must be a JSON object");

  // Only "command" and "args" are known: a misspelt member is refused rather
  // than silently ignored.
  std::uint32_t i = 1;
  for (std::uint32_t m = 0; m < doc->token(0).count; ++m) {
    const std::string_view key = doc->text_of(i);
    if (key != "command" && key != "args")
      return Error::make(Errc::invalid_argument, "request: unknown member '%.*s'",
                         static_cast<int>(key.size()), key.data());
    i = doc->token(i + 1).next;
  }
  const std::uint32_t name = doc->find(0, "command");
  if (name == 0) return Error::make(Errc::missing_field, "command: missing");
  if (doc->token(name).type != json::Type::string)
    return Error::make(Errc::invalid_argument, "command: must be a string");

  std::vector<std::string> words;
  if (const std::uint32_t args = doc->find(0, "args"); args != 0) {
    if (doc->token(args).type != json::Type::object)
      return Error::make(Errc::invalid_argument, "args: must be an object");
    std::uint32_t k = args + 1;
    for (std::uint32_t m = 0; m < doc->token(args).count; ++m) {
      const std::string key(doc->text_of(k));
      const json::Token& v = doc->token(k + 1);
      if (v.type != json::Type::number && v.type != json::Type::boolean)
        return Error::make(Errc::invalid_argument, "args.%s: must be a number", key.c_str());
      if (key.find('=') != std::string::npos)
        return Error::make(Errc::invalid_argument, "args: bad field name '%s'", key.c_str());
      char text[64];
      std::snprintf(text, sizeof(text), "%.17g", v.number);
      words.push_back(key + "=" + text);
      k = v.next;
    }
  }
  return ground::build_command(std::string(doc->text_of(name)), words);
}

}  // namespace petra::gnd
