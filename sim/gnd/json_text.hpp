// Small helpers for the JSON the ground station writes (HTTP answers and
// server-sent events): string escaping and one-member objects.
#pragma once

#include <string>
#include <string_view>

namespace petra::gnd {

// `s` as a JSON string literal, quotes included (control characters escaped).
std::string json_string(std::string_view s);

// {"error":"<message>"}: the body of every refused request.
std::string json_error(std::string_view message);

}  // namespace petra::gnd
