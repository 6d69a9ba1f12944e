// THE colours of the pictures an operator looks at: the onboard overlay
// product (fsw), `petra eval`'s disparity.png, overlay.png and PLY colours
// (sim/eval), and the ground station page (served as GET /api/palette);
// the pictures themselves are drawn once, by algo/chain/products.
// Grind plane colours are indexed by rank (the operator's plane k + 1 is
// kPlanes[k]); shadow is a dark violet so it never reads as the blue plane.
#pragma once

#include <cstdint>

namespace petra::palette {

struct Rgb8 {
  std::uint8_t r, g, b;
};

inline constexpr int kPlaneCount = 8;
inline constexpr Rgb8 kPlanes[kPlaneCount] = {{230, 40, 40},  {40, 110, 240}, {250, 200, 0},
                                              {200, 60, 220}, {0, 200, 200},  {255, 120, 0},
                                              {120, 220, 60}, {255, 255, 255}};
inline constexpr Rgb8 kGround{110, 140, 70};
inline constexpr Rgb8 kRock{215, 200, 170};
inline constexpr Rgb8 kShadow{70, 30, 90};
inline constexpr Rgb8 kRejected{150, 150, 170};
inline constexpr Rgb8 kNoData{0, 0, 0};  // no match, no point

// Disparity colour map, far (smallest disparity) to near (largest), linear
// between equally spaced stops: blue, cyan, green, yellow, red.
inline constexpr int kRampStops = 5;
inline constexpr Rgb8 kDisparityRamp[kRampStops] = {
    {30, 40, 200}, {0, 200, 230}, {40, 200, 60}, {250, 220, 0}, {230, 30, 30}};

// t in [0, 1] (0 far, 1 near) on the ramp.
constexpr Rgb8 disparity_colour(double t) {
  t = t < 0 ? 0 : (t > 1 ? 1 : t);
  const double x = t * (kRampStops - 1);
  const int i = x >= kRampStops - 2 ? kRampStops - 2 : static_cast<int>(x);
  const double f = x - i;
  const Rgb8 a = kDisparityRamp[i], b = kDisparityRamp[i + 1];
  auto mix = [f](std::uint8_t p, std::uint8_t q) {
    return static_cast<std::uint8_t>(p + f * (q - p));
  };
  return {mix(a.r, b.r), mix(a.g, b.g), mix(a.b, b.b)};
}

constexpr Rgb8 plane_colour(int rank) {
  return kPlanes[rank >= 0 && rank < kPlaneCount ? rank : kPlaneCount - 1];
}

}  // namespace petra::palette
