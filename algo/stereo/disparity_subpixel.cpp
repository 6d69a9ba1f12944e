#include "algo/stereo/disparity_subpixel.hpp"

#include <cmath>
#include <cstdint>

namespace petra {

namespace {

// Sum of squared differences between the left window at (x, y) and the right
// window at (x - d, y); the caller keeps both inside the images.
std::int64_t window_ssd(const ConstGray8View& l, const ConstGray8View& r, int x, int y, int d,
                        int rad) {
  std::int64_t sum = 0;
  for (int dy = -rad; dy <= rad; ++dy) {
    const std::uint8_t* lp = l.row(y + dy) + x - rad;
    const std::uint8_t* rp = r.row(y + dy) + x - d - rad;
    for (int k = 0; k <= 2 * rad; ++k) {
      const int e = static_cast<int>(lp[k]) - static_cast<int>(rp[k]);
      sum += e * e;
    }
  }
  return sum;
}

}  // namespace

Status validate(const SubpixelParams& p) {
  if (p.window_radius < 1 || p.window_radius > 7)
    return Error::make(Errc::out_of_range, "subpixel: window_radius %d not in 1..7",
                       p.window_radius);
  if (p.search_px < 0 || p.search_px > kMaxSearchPx)
    return Error::make(Errc::out_of_range, "subpixel: search_px %d not in 0..%d", p.search_px,
                       kMaxSearchPx);
  return {};
}

Result<long> refine_subpixel(const StereoInput& in, const SubpixelParams& params,
                             DisparityMap& map) {
  PETRA_TRY(validate(params));
  const ConstGray8View& l = in.left;
  const ConstGray8View& r = in.right;
  if (l.empty() || l.width() != r.width() || l.height() != r.height())
    return Error::make(Errc::invalid_argument, "subpixel: images %dx%d and %dx%d", l.width(),
                       l.height(), r.width(), r.height());
  const Rect& roi = map.roi;
  if (!roi.inside(l.width(), l.height()) || map.q4.width() != roi.w || map.q4.height() != roi.h)
    return Error::make(Errc::invalid_argument,
                       "subpixel: map %dx%d for ROI (%d,%d %dx%d) of a %dx%d image", map.q4.width(),
                       map.q4.height(), roi.x, roi.y, roi.w, roi.h, l.width(), l.height());
  const int rad = params.window_radius;
  const int W = l.width(), H = l.height();
  long refined = 0;
  for (int j = 0; j < roi.h; ++j) {
    const int y = roi.y + j;
    if (y - rad < 0 || y + rad >= H) continue;
    std::int16_t* row = map.q4.row(j);
    for (int i = 0; i < roi.w; ++i) {
      if (!is_valid_disparity(row[i])) continue;
      const int x = roi.x + i;
      // Integer part: the nearest whole pixel (the input may already be finer).
      const int d = static_cast<int>(std::lround(disparity_px(row[i])));
      const int reach = params.search_px + 1;
      if (x - rad < 0 || x + rad >= W || x - d - reach - rad < 0 || x - d + reach + rad >= W)
        continue;
      std::int64_t c[2 * kMaxSearchPx + 3];
      for (int k = 0; k <= 2 * reach; ++k) c[k] = window_ssd(l, r, x, y, d - reach + k, rad);
      // The best of d - search .. d + search (a whole-pixel label can be a
      // little off), then the parabola through it and its neighbours.
      int b = reach;
      for (int k = 1; k < 2 * reach; ++k)
        if (c[k] < c[b]) b = k;
      // cppcheck-suppress uninitvar ; c[0 .. 2 reach] are all set above and 1 <= b < 2 reach
      const std::int64_t cm = c[b - 1], c0 = c[b], cp = c[b + 1];
      if (!(c0 <= cm && c0 <= cp && cm + cp > 2 * c0)) continue;
      const double offset =
          static_cast<double>(cm - cp) / (2.0 * static_cast<double>(cm - 2 * c0 + cp));
      row[i] = disparity_q4(d - reach + b + offset);
      ++refined;
    }
  }
  return refined;
}

}  // namespace petra
