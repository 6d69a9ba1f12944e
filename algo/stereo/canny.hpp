// Canny edge detector in integer arithmetic (docs/method.md 2b step 1), on an area
// of an 8-bit gray image: 5x5 binomial smoothing (sigma ~ 1), 3x3 Sobel,
// non-maximum suppression along the gradient quantised to four sectors, and
// hysteresis from strong to weak pixels with a bounded explicit stack (no
// recursion). Pixels outside the image are replicated from its border.
//
// Output: `edges` (the area's size), 0 for no edge, otherwise kEdgeBit plus
// the gradient sector and the sign of the horizontal gradient, which the
// matcher uses to pair only compatible edges.
// Memory (Arena): canny_scratch_bytes(w, h) = (w+4)(h+4) smoothed bytes
// + 6 (w+2)(h+2) gradient and magnitude bytes + 4 w h stack bytes + row
// buffers (+ alignment), about 11 bytes per area pixel. Released on return.
#pragma once

#include <cstddef>
#include <cstdint>

#include "algo/core/arena.hpp"
#include "algo/core/image_view.hpp"
#include "algo/core/result.hpp"

namespace petra {

inline constexpr std::uint8_t kEdgeBit = 0x80;
inline constexpr std::uint8_t kEdgeGxNegative = 0x40;  // gradient points to -x
inline constexpr std::uint8_t kEdgeSectorMask = 0x03;

// Gradient direction, quantised (image y axis points down).
enum EdgeSector : std::uint8_t {
  kSectorHorizontal = 0,  // gradient along x: a vertical edge
  kSectorDiagonal = 1,    // gradient along (1, 1)
  kSectorVertical = 2,    // gradient along y: a horizontal edge
  kSectorAntiDiagonal = 3,
};

constexpr bool is_edge(std::uint8_t e) {
  return (e & kEdgeBit) != 0;
}
constexpr int edge_sector(std::uint8_t e) {
  return e & kEdgeSectorMask;
}

struct CannyParams {
  // Thresholds on |gx| + |gy| of the smoothed image (Sobel gain 4: a step of
  // g gray levels gives about 2g after smoothing). 0 < low <= high.
  int low = 24;
  int high = 64;
};

struct CannyStats {
  long edge_pixels = 0;
  long strong_pixels = 0;  // seeds of the hysteresis (>= high)
};

std::size_t canny_scratch_bytes(int width, int height);

// Errors: empty area, area outside the image, `edges` not the area's size,
// bad thresholds, an area whose h * 2^ceil(log2 w) exceeds 2^32 (far beyond
// any camera), scratch too small (names the buffer).
Result<CannyStats> canny(ConstGray8View image, Rect area, const CannyParams& params, Arena& scratch,
                         Gray8View edges);

}  // namespace petra
