#include "sim/gnd/json_text.hpp"

#include <cstdio>

namespace petra::gnd {

std::string json_string(std::string_view s) {
  std::string o = "\"";
  for (const char c : s) {
    if (c == '"' || c == '\\') {
      o += '\\';
      o += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char esc[8];
      std::snprintf(esc, sizeof(esc), "\\u%04x", static_cast<unsigned>(c));
      o += esc;
    } else {
      o += c;
    }
  }
  return o + "\"";
}

std::string json_error(std::string_view message) {
  return "{\"error\":" + json_string(message) + "}";
}

}  // namespace petra::gnd
