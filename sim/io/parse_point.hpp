// Strict parsing of "u,v" command-line pixel positions (two integers, no
// extra text), e.g. the operator's click.
#pragma once

#include <string>

#include "algo/core/result.hpp"

namespace petra::io {

struct PixelPoint {
  int u = 0;
  int v = 0;
};

Result<PixelPoint> parse_point(const std::string& text);

}  // namespace petra::io
