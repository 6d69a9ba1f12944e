// Ground side of the uplink: builds a Command from its name and
// `field=value` words (names and ranges from cmd/command_defs.hpp), and keeps
// the command counter in a file so every command signed with a key carries a
// larger counter than the last.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "algo/core/result.hpp"
#include "cmd/auth.hpp"
#include "cmd/commands.hpp"

namespace petra::ground {

// NAME is case-insensitive; words are field=value. Every field is required,
// except SELECT_ROI's click (click_u_px and click_v_px together, or neither;
// has_click follows from them). Values outside a field's range, unknown or
// repeated fields, a click outside the ROI and an unknown parameter or a value
// outside its range are refused here, naming the field.
Result<cmd::Command> build_command(const std::string& name, const std::vector<std::string>& words);

// Text listing every command and its fields (for --help and errors).
std::string command_usage();

// Reads the uplink key file; a file error names the system's reason.
Result<cmd::AuthKey> load_uplink_key(const std::string& path);

// Reads the counter file (0 when absent), returns last + 1 and stores it.
Result<std::uint32_t> next_counter(const std::string& path);

}  // namespace petra::ground
