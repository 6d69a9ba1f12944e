// Synthetic rectified stereo pairs with known disparity for the matcher
// tests: a textured background plane and an optional textured box in front
// of it. Textures are value noise (random samples on an integer lattice,
// linear in x), so a sub-pixel disparity is an exact resampling.
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "algo/core/image_view.hpp"

namespace petra::test {

class ValueNoise {
 public:
  ValueNoise(int w, int h, std::uint32_t seed, int lo = 30, int hi = 225)
      : w_(w), h_(h), v_(static_cast<std::size_t>(w) * h) {
    std::mt19937 rng(seed);
    std::uniform_int_distribution<int> g(lo, hi);
    for (auto& x : v_) x = static_cast<float>(g(rng));
  }
  // Linear in x between lattice samples (clamped at the ends).
  float at(double x, int y) const {
    const double c = std::clamp(x, 0.0, static_cast<double>(w_ - 1));
    const int x0 = std::min(static_cast<int>(c), w_ - 2);
    const double f = c - x0;
    const float* row = v_.data() + static_cast<std::size_t>(std::clamp(y, 0, h_ - 1)) * w_;
    return static_cast<float>((1 - f) * static_cast<double>(row[x0]) +
                              f * static_cast<double>(row[x0 + 1]));
  }

 private:
  int w_, h_;
  std::vector<float> v_;
};

struct StereoScene {
  int w = 0, h = 0;
  std::vector<std::uint8_t> left, right;
  std::vector<float> truth;  // left-view disparity; NaN where occluded in the right view

  ConstGray8View lv() const { return {left.data(), w, h}; }
  ConstGray8View rv() const { return {right.data(), w, h}; }
  float d(int x, int y) const { return truth[static_cast<std::size_t>(y) * w + x]; }
};

// A scene of w x h pixels, its images and truth to be filled.
inline StereoScene sized_scene(int w, int h) {
  StereoScene s;
  s.w = w;
  s.h = h;
  s.left.resize(static_cast<std::size_t>(w) * h);
  s.right.resize(s.left.size());
  s.truth.resize(s.left.size());
  return s;
}

// Background at disparity d_bg; optional box [bx, bx+bw) x [by, by+bh) (in
// the left view) at d_fg.
inline StereoScene make_scene(int w, int h, double d_bg, double d_fg = 0, int bx = 0, int by = 0,
                              int bw = 0, int bh = 0, std::uint32_t seed = 1) {
  StereoScene s = sized_scene(w, h);
  const ValueNoise bg(w + 300, h, seed), fg(w + 300, h, seed + 7);
  const int off = 150;  // texture coordinates stay positive for negative disparities
  auto in_box = [&](double xl, int y) {
    return bw > 0 && y >= by && y < by + bh && xl >= bx && xl < bx + bw;
  };
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * w + x;
      const bool box = in_box(x, y);
      s.left[i] =
          static_cast<std::uint8_t>(std::lround(box ? fg.at(x + off, y) : bg.at(x + off, y)));
      // Right pixel xr sees the box if xr + d_fg falls in it, else the background.
      const double xf = x + d_fg;
      s.right[i] = static_cast<std::uint8_t>(
          std::lround(in_box(xf, y) ? fg.at(xf + off, y) : bg.at(x + d_bg + off, y)));
      // Truth; a background pixel whose right match is hidden by the box is occluded.
      const double d = box ? d_fg : d_bg;
      const bool occluded = !box && in_box(x - d_bg + d_fg, y);
      s.truth[i] = occluded ? std::numeric_limits<float>::quiet_NaN() : static_cast<float>(d);
    }
  return s;
}

// A surface whose disparity grows down the image by per_row px per row (a
// face turned up towards the sky): d(y) = d_top + per_row y, no occlusion.
inline StereoScene make_tilted_scene(int w, int h, double d_top, double per_row,
                                     std::uint32_t seed = 1) {
  StereoScene s = sized_scene(w, h);
  const ValueNoise tex(w + 300, h, seed);
  const int off = 150;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * w + x;
      const double d = d_top + per_row * y;
      s.left[i] = static_cast<std::uint8_t>(std::lround(tex.at(x + off, y)));
      s.right[i] = static_cast<std::uint8_t>(std::lround(tex.at(x + d + off, y)));
      s.truth[i] = static_cast<float>(d);
    }
  return s;
}

}  // namespace petra::test
