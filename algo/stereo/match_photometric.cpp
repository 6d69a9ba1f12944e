#include "algo/stereo/match_photometric.hpp"

#include <algorithm>
#include <cstdint>
#include <cstdlib>

namespace petra::match {

namespace {

struct GrayStats {
  std::int64_t count = 0;
  std::int64_t mean_q8 = 0;  // 1/256 gray level
  std::int64_t mad_q8 = 0;   // mean absolute deviation, 1/256 gray level
};

// Rounded quotient, halves away from zero (b > 0).
std::int64_t div_round(std::int64_t a, std::int64_t b) {
  return a >= 0 ? (a + b / 2) / b : -((-a + b / 2) / b);
}

// Statistics of the means of 4x2 pixel blocks, not of single pixels: a view
// resampled at a sub-pixel offset (rectification, a sub-pixel disparity) has
// a smaller pixel-to-pixel deviation than the other, which a per-pixel
// estimate took for a gain (1.3 on white-noise texture); block means hardly
// change with it.
constexpr int kBlockW = 4, kBlockH = 2;

GrayStats stats_of(ConstGray8View img, Rect area) {
  GrayStats s;
  const int x0 = std::max(area.x, 0), y0 = std::max(area.y, 0);
  const int x1 = std::min(area.x + area.w, img.width());
  const int y1 = std::min(area.y + area.h, img.height());
  const int bw = (x1 - x0) / kBlockW, bh = (y1 - y0) / kBlockH;
  if (bw <= 0 || bh <= 0) return s;
  std::int32_t hist[256] = {};
  for (int by = 0; by < bh; ++by) {
    const std::uint8_t* r0 = &img(0, y0 + by * kBlockH);
    const std::uint8_t* r1 = &img(0, y0 + by * kBlockH + 1);
    for (int bx = 0; bx < bw; ++bx) {
      const int x = x0 + bx * kBlockW;
      const int sum =
          r0[x] + r0[x + 1] + r0[x + 2] + r0[x + 3] + r1[x] + r1[x + 1] + r1[x + 2] + r1[x + 3];
      ++hist[(sum + kBlockW * kBlockH / 2) / (kBlockW * kBlockH)];
    }
  }
  std::int64_t sum = 0;
  for (int g = 0; g < 256; ++g) {
    s.count += hist[g];
    sum += static_cast<std::int64_t>(hist[g]) * g;
  }
  s.mean_q8 = div_round(sum * 256, s.count);
  std::int64_t dev = 0;
  for (int g = 0; g < 256; ++g) dev += hist[g] * std::llabs(g * 256 - s.mean_q8);
  s.mad_q8 = div_round(dev, s.count);
  return s;
}

}  // namespace

GrayMap identity_gray_map() {
  GrayMap m;
  for (int g = 0; g < 256; ++g) m.level[g] = static_cast<std::uint8_t>(g);
  return m;
}

GrayMap right_to_left_gray_map(ConstGray8View left, Rect left_area, ConstGray8View right,
                               Rect right_area) {
  const GrayStats l = stats_of(left, left_area), r = stats_of(right, right_area);
  GrayMap m = identity_gray_map();
  if (l.count == 0 || r.count == 0) return m;
  // gain in 1/256: mad_L / mad_R within [1/4, 4]; a flat area keeps gain 1.
  std::int64_t gain_q8 = 256;
  if (l.mad_q8 > 0 && r.mad_q8 > 0)
    gain_q8 = std::clamp<std::int64_t>(div_round(l.mad_q8 * 256, r.mad_q8), 256 / kMaxGrayGain,
                                       256 * kMaxGrayGain);
  // level(v) in 1/256: mean_L + (v - mean_R) gain.
  const std::int64_t offset_q8 = l.mean_q8 - div_round(r.mean_q8 * gain_q8, 256);
  m.gain_q8 = static_cast<int>(gain_q8);
  m.offset_q8 = static_cast<int>(offset_q8);
  for (int g = 0; g < 256; ++g) {
    const std::int64_t v = div_round(offset_q8 + g * gain_q8, 256);
    m.level[g] = static_cast<std::uint8_t>(std::clamp<std::int64_t>(v, 0, 255));
  }
  return m;
}

GrayMap gray_map_for_roi(ConstGray8View left, ConstGray8View right, Rect roi, int disp_min,
                         int disp_max) {
  const int mid = disp_min + (disp_max - disp_min) / 2;
  // Left columns x whose right column x - mid lies inside the image.
  const int x0 = std::max(roi.x, mid), x1 = std::min(roi.x + roi.w, right.width() + mid);
  if (x1 <= x0) return identity_gray_map();
  return right_to_left_gray_map(left, {x0, roi.y, x1 - x0, roi.h}, right,
                                {x0 - mid, roi.y, x1 - x0, roi.h});
}

void apply_gray_map(const GrayMap& map, const std::uint8_t* src, int n, std::uint8_t* dst) {
  for (int i = 0; i < n; ++i) dst[i] = map.level[src[i]];
}

}  // namespace petra::match
