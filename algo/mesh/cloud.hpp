// Point-cloud element types shared by the reconstruction units. A cloud is
// structure-of-arrays in caller memory: positions (world frame of calib.json,
// mm) in one span, the rectified left pixel each came from in another, so the
// geometry templates see plain Eigen vectors.
#pragma once

#include <cstdint>

namespace petra {

// Rectified left-image pixel of a matched point (integer grid: the disparity
// map's pixel (x, y) is (roi.x + x, roi.y + y)).
struct PixelPos {
  std::int16_t u = 0;
  std::int16_t v = 0;
};

// Per-point class from rock/ground segmentation.
enum class PointClass : std::uint8_t { ground = 0, rock = 1 };

}  // namespace petra
