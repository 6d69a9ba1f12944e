#include "algo/stereo/downsample.hpp"

namespace petra {

Status downsample_box(ConstGray8View src, Rect region, int factor, Gray8View dst) {
  if (factor < 1 || factor > 8)
    return Error::make(Errc::invalid_argument, "downsample: factor %d not in 1..8", factor);
  if (!region.inside(src.width(), src.height()))
    return Error::make(Errc::out_of_range,
                       "downsample: region (%d,%d %dx%d) outside the %dx%d image", region.x,
                       region.y, region.w, region.h, src.width(), src.height());
  const int x0 = (region.x + factor - 1) / factor, y0 = (region.y + factor - 1) / factor;
  const int x1 = (region.x + region.w) / factor, y1 = (region.y + region.h) / factor;
  if (x1 > dst.width() || y1 > dst.height())
    return Error::make(Errc::out_of_range, "downsample: %dx%d destination too small", dst.width(),
                       dst.height());
  const int area = factor * factor;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) {
      int sum = 0;
      for (int dy = 0; dy < factor; ++dy) {
        const std::uint8_t* row = src.row(y * factor + dy) + x * factor;
        for (int dx = 0; dx < factor; ++dx) sum += row[dx];
      }
      dst(x, y) = static_cast<std::uint8_t>((sum + area / 2) / area);
    }
  return {};
}

}  // namespace petra
