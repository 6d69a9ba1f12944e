// Strict parsing of "x,y,w,h" command-line rectangles (four integers, no
// extra text), shared by the subcommands that take an ROI.
#pragma once

#include <string>

#include "algo/core/image_view.hpp"
#include "algo/core/result.hpp"

namespace petra::io {

Result<Rect> parse_roi(const std::string& text);

}  // namespace petra::io
