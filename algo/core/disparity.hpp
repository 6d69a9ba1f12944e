// The disparity map every matcher writes and every later stage reads.
// Values are fixed-point (1/16 px, "Q4") in int16_t so matching and filtering
// stay in integer arithmetic; kInvalidDisparity marks pixels with no match
// (shadow, occlusion, rejected). Coordinates are those of the RECTIFIED left
// image (algo/camera/rectify_geometry): element (x, y) of `q4` is rectified pixel
// (roi.x + x, roi.y + y), and its match is right pixel (roi.x + x - d, roi.y + y).
#pragma once

#include <cstdint>
#include <limits>

#include "algo/core/image_view.hpp"

namespace petra {

inline constexpr int kDisparityFracBits = 4;
inline constexpr int kDisparityScale = 1 << kDisparityFracBits;  // 16 steps per pixel
inline constexpr std::int16_t kInvalidDisparity = std::numeric_limits<std::int16_t>::min();

struct DisparityMap {
  ImageView<std::int16_t> q4;  // disparity * 16, or kInvalidDisparity
  Rect roi;                    // where q4 lies in the rectified left image
};

struct ConstDisparityMap {
  ImageView<const std::int16_t> q4;
  Rect roi;
  ConstDisparityMap() = default;
  ConstDisparityMap(ImageView<const std::int16_t> v, Rect r) : q4(v), roi(r) {}
  ConstDisparityMap(const DisparityMap& m) : q4(m.q4), roi(m.roi) {}  // NOLINT(implicit)
};

constexpr bool is_valid_disparity(std::int16_t q) {
  return q != kInvalidDisparity;
}
constexpr double disparity_px(std::int16_t q) {
  return static_cast<double>(q) / kDisparityScale;
}
// Nearest Q4 value of a disparity in pixels (callers keep |d| < 2047).
constexpr std::int16_t disparity_q4(double d_px) {
  return static_cast<std::int16_t>(d_px >= 0 ? d_px * kDisparityScale + 0.5
                                             : d_px * kDisparityScale - 0.5);
}

}  // namespace petra
