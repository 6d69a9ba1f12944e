// A disparity map given on the command line (`--disparity D.pfm`: a ground
// truth, a recorded or another matcher's map of the rectified left view) in
// the chain's Q4 form, for `petra eval` and `petra propose` to replay instead
// of matching. Non-finite or absurd values (|d| >= 2000 px) become invalid.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "algo/core/result.hpp"

namespace petra::io {

// The whole map, row-major, width x height; refused when it is another size.
Result<std::vector<std::int16_t>> read_disparity_q4(const std::string& path, int width, int height);

}  // namespace petra::io
