// The browser's command request, checked before anything is signed:
//   {"command": "SELECT_ROI", "args": {"x_px": 120, "y_px": 80, ...}}
// "args" is optional (fields default as in `petra cmd`). Every problem is
// refused with a message naming the field: body not JSON, unknown member,
// unknown command, unknown field, value not a number, value out of range.
// Names and ranges come from cmd/command_defs.hpp (via ground::build_command).
#pragma once

#include <string_view>

#include "algo/core/result.hpp"
#include "cmd/commands.hpp"

namespace petra::gnd {

// Largest request body accepted (the largest command has eight fields).
inline constexpr std::size_t kMaxRequestBytes = 4096;

Result<cmd::Command> parse_command_request(std::string_view body);

}  // namespace petra::gnd
