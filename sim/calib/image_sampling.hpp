// Bilinear sampling and smoothing shared by the chessboard detector. Pixel
// (i, j) has its centre at (u, v) = (i, j); samples outside the image clamp to
// the border (callers keep their windows inside, the clamp only guards).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "algo/core/image_view.hpp"
#include "sim/io/image_io.hpp"

namespace petra::calib {

template <class T>
double sample_bilinear(ImageView<const T> img, double u, double v) {
  const double uc = std::clamp(u, 0.0, img.width() - 1.0);
  const double vc = std::clamp(v, 0.0, img.height() - 1.0);
  const int x0 = std::min(static_cast<int>(uc), img.width() - 2 < 0 ? 0 : img.width() - 2);
  const int y0 = std::min(static_cast<int>(vc), img.height() - 2 < 0 ? 0 : img.height() - 2);
  const int x1 = std::min(x0 + 1, img.width() - 1);
  const int y1 = std::min(y0 + 1, img.height() - 1);
  const double a = uc - x0, b = vc - y0;
  const double top =
      (1 - a) * static_cast<double>(img(x0, y0)) + a * static_cast<double>(img(x1, y0));
  const double bot =
      (1 - a) * static_cast<double>(img(x0, y1)) + a * static_cast<double>(img(x1, y1));
  return (1 - b) * top + b * bot;
}

// Gray image to float with a separable binomial blur [1 4 6 4 1]/16 (sigma
// about 1 px): takes the edge off JPEG noise before corner responses.
io::FloatImage smooth_binomial5(ConstGray8View img);

// Float copy without smoothing.
io::FloatImage to_float(ConstGray8View img);

}  // namespace petra::calib
