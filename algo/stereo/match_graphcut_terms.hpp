// The per-pixel terms of the graph-cut energy (algo/stereo/match_graphcut.hpp), kept
// apart so the expansion code and the parameter choice share one definition.
// Gray values are doubled so half-pixel samples stay integers. Every gray value
// is read through a level table (algo/stereo/match_photometric: the right view's
// levels on the left's scale; the identity for the left view).
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstdlib>

#include "algo/core/image_view.hpp"

namespace petra::gc {

// Doubled gray value of a pixel and the doubled range [lo, hi] spanned by it
// and its half-pixel samples towards the 4 neighbours (clamped at the border).
struct Sample {
  std::uint16_t v;
  std::uint16_t lo;
  std::uint16_t hi;
};

inline Sample half_pixel_sample(ConstGray8View img, const std::uint8_t* level, int x, int y) {
  const int i = level[img(x, y)];
  const int l = level[img(std::max(x - 1, 0), y)];
  const int r = level[img(std::min(x + 1, img.width() - 1), y)];
  const int u = level[img(x, std::max(y - 1, 0))];
  const int d = level[img(x, std::min(y + 1, img.height() - 1))];
  const int lo = i + std::min({i, l, r, u, d});
  const int hi = i + std::max({i, l, r, u, d});
  return {static_cast<std::uint16_t>(2 * i), static_cast<std::uint16_t>(lo),
          static_cast<std::uint16_t>(hi)};
}

// Birchfield-Tomasi distance (doubled), clipped at clip2, squared: cost units
// of 1/4 gray level squared.
inline std::int32_t bt_cost(const Sample& l, const Sample& r, std::int32_t clip2) {
  const int d_lr = std::max({0, l.v - r.hi, r.lo - l.v});
  const int d_rl = std::max({0, r.v - l.hi, l.lo - r.v});
  const int d = std::min({d_lr, d_rl, static_cast<int>(clip2)});
  return d * d;
}

// Bit 0: intensity edge towards the right neighbour; bit 1: towards the lower
// one (|difference| >= threshold; only where that neighbour is in the region).
inline std::uint8_t edge_flags(ConstGray8View img, const std::uint8_t* level, int x, int y,
                               bool has_right, bool has_down, int threshold) {
  const int i = level[img(x, y)];
  std::uint8_t f = 0;
  if (has_right && std::abs(i - level[img(x + 1, y)]) >= threshold) f |= 1;
  if (has_down && std::abs(i - level[img(x, y + 1)]) >= threshold) f |= 2;
  return f;
}

}  // namespace petra::gc
