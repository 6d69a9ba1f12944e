// calib.json (contract in docs/icd.md): text <-> StereoRig. Pure text
// processing over caller memory; the caller reads or writes the file.
#pragma once

#include <span>
#include <string_view>

#include "algo/camera/camera_model.hpp"
#include "algo/core/result.hpp"

namespace petra {

// Parses and validates. Errors name the field, e.g. "left.f: missing" or
// "right.R: not orthonormal".
Result<StereoRig> parse_calib_json(std::string_view text);

// Writes the contract form; doubles round-trip exactly.
Result<std::size_t> format_calib_json(const StereoRig& rig, std::span<char> out);

}  // namespace petra
