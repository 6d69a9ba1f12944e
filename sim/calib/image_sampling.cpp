#include "sim/calib/image_sampling.hpp"

namespace petra::calib {

io::FloatImage to_float(ConstGray8View img) {
  io::FloatImage out(img.width(), img.height());
  for (int y = 0; y < img.height(); ++y)
    for (int x = 0; x < img.width(); ++x) out.view()(x, y) = static_cast<float>(img(x, y));
  return out;
}

io::FloatImage smooth_binomial5(ConstGray8View img) {
  const int w = img.width(), h = img.height();
  constexpr float kTaps[5] = {1.f / 16, 4.f / 16, 6.f / 16, 4.f / 16, 1.f / 16};
  io::FloatImage rows(w, h), out(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      float s = 0;
      for (int k = -2; k <= 2; ++k)
        s += kTaps[k + 2] * static_cast<float>(img(std::clamp(x + k, 0, w - 1), y));
      rows.view()(x, y) = s;
    }
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      float s = 0;
      for (int k = -2; k <= 2; ++k) s += kTaps[k + 2] * rows.view()(x, std::clamp(y + k, 0, h - 1));
      out.view()(x, y) = s;
    }
  return out;
}

}  // namespace petra::calib
