// 3x3 median over the valid pixels of a disparity map (algo/core/disparity.hpp):
// each valid pixel with at least five valid pixels in its 3x3 neighbourhood
// takes their median (the upper one for an even count); invalid pixels stay
// invalid and are never created. Removes isolated spikes without moving
// depth edges. Memory: median3x3_scratch(width) int16 from the caller.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "algo/core/image_view.hpp"
#include "algo/core/result.hpp"

namespace petra {

constexpr std::size_t median3x3_scratch(int width) {
  return width > 0 ? 3 * (static_cast<std::size_t>(width) + 2) : 0;
}

// Errors: scratch smaller than median3x3_scratch(width).
Status median3x3_valid(ImageView<std::int16_t> disparity, std::span<std::int16_t> scratch);

}  // namespace petra
