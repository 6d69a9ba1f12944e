// Test-local Middlebury loader and bad-1 scorer on the convention of
// ../shared/data/README.md (nonocc by cross-checking the two ground truths,
// strict and background-filled counts). Used by the graph-cut tests until the
// shared scorer (sim/eval/middlebury) is available.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "algo/disparity.hpp"
#include "sim/io/image_io.hpp"

namespace petra::test {

struct MiddleburyScene {
  std::string name;
  std::string dir;  // relative to ../shared/data
  std::string left, right, gt_left, gt_right;  // gt_right may be empty
  double scale = 1;
  int disp_min = 0, disp_max = 0;
};

inline std::vector<MiddleburyScene> middlebury_scenes() {
  return {
      {"tsukuba", "middlebury/tsukuba", "scene1.row3.col3.ppm", "scene1.row3.col4.ppm",
       "truedisp.row3.col3.pgm", "", 16, 0, 15},
      {"venus", "middlebury/venus", "im2.ppm", "im6.ppm", "disp2.pgm", "disp6.pgm", 8, 0, 19},
      {"teddy", "middlebury/teddy", "im2.png", "im6.png", "disp2.png", "disp6.png", 4, 0, 59},
      {"cones", "middlebury/cones", "im2.png", "im6.png", "disp2.png", "disp6.png", 4, 0, 59},
      {"sawtooth", "middlebury/sawtooth", "im2.ppm", "im6.ppm", "disp2.pgm", "disp6.pgm", 8, 0, 19},
      {"map", "middlebury/map", "im0.pgm", "im1.pgm", "disp0.pgm", "disp1.pgm", 8, 0, 29},
      {"Aloe", "middlebury2006/Aloe", "view1.png", "view5.png", "disp1.png", "disp5.png", 2, 0, 111},
      {"Baby1", "middlebury2006/Baby1", "view1.png", "view5.png", "disp1.png", "disp5.png", 2, 0, 79},
  };
}

struct LoadedScene {
  io::GrayImage left, right, gt_left, gt_right;
};

inline std::string shared_data(const std::string& rel) {
  return std::string(PETRA_SOURCE_DIR) + "/../shared/data/" + rel;
}

inline bool load_scene(const MiddleburyScene& s, LoadedScene& out, std::string& error) {
  auto get = [&](const std::string& file, io::GrayImage& img) {
    auto r = io::read_gray_image(shared_data(s.dir + "/" + file));
    if (!r) {
      error = r.error().message;
      return false;
    }
    img = std::move(*r);
    return true;
  };
  if (!get(s.left, out.left) || !get(s.right, out.right) || !get(s.gt_left, out.gt_left)) return false;
  if (!s.gt_right.empty() && !get(s.gt_right, out.gt_right)) return false;
  return true;
}

struct Bad1 {
  double strict_nonocc = 0, strict_all = 0, filled_nonocc = 0, filled_all = 0;
};

// Invalid pixels take the smaller of the nearest valid disparities to their
// left and right on the row.
inline std::vector<double> fill_background(const std::vector<double>& d, int w, int h) {
  std::vector<double> out(d);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if (!std::isnan(d[y * w + x])) continue;
      double l = NAN, r = NAN;
      for (int k = x - 1; k >= 0; --k)
        if (!std::isnan(d[y * w + k])) { l = d[y * w + k]; break; }
      for (int k = x + 1; k < w; ++k)
        if (!std::isnan(d[y * w + k])) { r = d[y * w + k]; break; }
      out[y * w + x] = std::isnan(l) ? r : std::isnan(r) ? l : std::min(l, r);
    }
  return out;
}

inline Bad1 score_bad1(const MiddleburyScene& s, const LoadedScene& sc, ConstDisparityMap map) {
  const int w = sc.left.width, h = sc.left.height;
  std::vector<double> d(w * h, NAN);
  for (int y = 0; y < map.roi.h; ++y)
    for (int x = 0; x < map.roi.w; ++x) {
      const std::int16_t q = map.q4(x, y);
      if (is_valid_disparity(q)) d[(map.roi.y + y) * w + map.roi.x + x] = disparity_px(q);
    }
  const std::vector<double> filled = fill_background(d, w, h);
  long n_all = 0, n_nonocc = 0, b[4] = {0, 0, 0, 0};
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const int g = sc.gt_left.pixels[y * w + x];
      if (g == 0) continue;
      const double gt = g / s.scale;
      bool nonocc = true;
      if (!sc.gt_right.pixels.empty()) {
        const int xr = x - static_cast<int>(std::lround(gt));
        nonocc = xr >= 0 && xr < w &&
                 std::abs(sc.gt_right.pixels[y * w + xr] / s.scale - gt) <= 1.0;
      }
      const bool bad_strict = std::isnan(d[y * w + x]) || std::abs(d[y * w + x] - gt) > 1.0;
      const bool bad_filled = std::isnan(filled[y * w + x]) || std::abs(filled[y * w + x] - gt) > 1.0;
      ++n_all;
      b[0] += bad_strict;
      b[1] += bad_filled;
      if (nonocc) {
        ++n_nonocc;
        b[2] += bad_strict;
        b[3] += bad_filled;
      }
    }
  Bad1 r;
  r.strict_all = 100.0 * static_cast<double>(b[0]) / static_cast<double>(std::max(1L, n_all));
  r.filled_all = 100.0 * static_cast<double>(b[1]) / static_cast<double>(std::max(1L, n_all));
  r.strict_nonocc = 100.0 * static_cast<double>(b[2]) / static_cast<double>(std::max(1L, n_nonocc));
  r.filled_nonocc = 100.0 * static_cast<double>(b[3]) / static_cast<double>(std::max(1L, n_nonocc));
  return r;
}

}  // namespace petra::test
