// Ground side of the uplink: builds a Command from its name and
// `field=value` words (names and ranges from cmd/command_defs.hpp), and keeps
// the command counter in a file so every command signed with a key carries a
// larger counter than the last.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "algo/core/result.hpp"
#include "cmd/commands.hpp"

namespace petra::ground {

// NAME is case-insensitive; words are field=value (every field is optional and
// defaults to 0, except has_click which is set by giving click_u_px/click_v_px).
// Values outside a field's range are refused here, naming the field.
Result<cmd::Command> build_command(const std::string& name, const std::vector<std::string>& words);

// Text listing every command and its fields (for --help and errors).
std::string command_usage();

// Reads the counter file (0 when absent), returns last + 1 and stores it.
Result<std::uint32_t> next_counter(const std::string& path);

}  // namespace petra::ground
