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

GrayStats stats_of_histogram(const std::int32_t* hist) {
  GrayStats s;
  std::int64_t sum = 0;
  for (int g = 0; g < 256; ++g) {
    s.count += hist[g];
    sum += static_cast<std::int64_t>(hist[g]) * g;
  }
  if (s.count == 0) return s;
  s.mean_q8 = div_round(sum * 256, s.count);
  std::int64_t dev = 0;
  for (int g = 0; g < 256; ++g) dev += hist[g] * std::llabs(g * 256 - s.mean_q8);
  s.mad_q8 = div_round(dev, s.count);
  return s;
}

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
  return stats_of_histogram(hist);
}

}  // namespace

GrayMap linear_gray_map(std::int64_t gain_q8, std::int64_t offset_q8) {
  GrayMap m;
  m.gain_q8 = static_cast<int>(gain_q8);
  m.offset_q8 = static_cast<int>(offset_q8);
  for (int g = 0; g < 256; ++g) {
    const std::int64_t v = div_round(offset_q8 + g * gain_q8, 256);
    m.level[g] = static_cast<std::uint8_t>(std::clamp<std::int64_t>(v, 0, 255));
  }
  return m;
}

GrayMap identity_gray_map() {
  GrayMap m;
  for (int g = 0; g < 256; ++g) m.level[g] = static_cast<std::uint8_t>(g);
  return m;
}

namespace {
GrayMap map_of_stats(const GrayStats& l, const GrayStats& r) {
  GrayMap m = identity_gray_map();
  if (l.count == 0 || r.count == 0) return m;
  // gain in 1/256: mad_L / mad_R within [1/4, 4]; a flat area keeps gain 1.
  std::int64_t gain_q8 = 256;
  if (l.mad_q8 > 0 && r.mad_q8 > 0)
    gain_q8 = std::clamp<std::int64_t>(div_round(l.mad_q8 * 256, r.mad_q8), 256 / kMaxGrayGain,
                                       256 * kMaxGrayGain);
  // level(v) in 1/256: mean_L + (v - mean_R) gain.
  return linear_gray_map(gain_q8, l.mean_q8 - div_round(r.mean_q8 * gain_q8, 256));
}
}  // namespace

GrayMap right_to_left_gray_map(ConstGray8View left, Rect left_area, ConstGray8View right,
                               Rect right_area) {
  return map_of_stats(stats_of(left, left_area), stats_of(right, right_area));
}

namespace {

// The 5x5 window at (x, y): its sum, and the absolute deviation of its 2x2
// block sums (the blocks, not single pixels: a view resampled at a sub-pixel
// offset has a smaller pixel-to-pixel deviation, which read as a gain).
struct WindowSums {
  int sum = 0;
  int dev = 0;  // sum over the 16 blocks of |16 block - sum of blocks|
};
WindowSums window_sums(ConstGray8View img, int x, int y) {
  constexpr int n = 2 * kPairWindowRadius + 1;
  int v[n][n];
  for (int j = 0; j < n; ++j) {
    const std::uint8_t* r = img.row(std::clamp(y + j - kPairWindowRadius, 0, img.height() - 1));
    for (int i = 0; i < n; ++i)
      v[j][i] = r[std::clamp(x + i - kPairWindowRadius, 0, img.width() - 1)];
  }
  WindowSums w;
  int blocks[n - 1][n - 1];
  int total = 0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) w.sum += v[j][i];
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i) {
      blocks[j][i] = v[j][i] + v[j][i + 1] + v[j + 1][i] + v[j + 1][i + 1];
      total += blocks[j][i];
    }
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i) w.dev += std::abs((n - 1) * (n - 1) * blocks[j][i] - total);
  return w;
}

// The pair's own gain (left deviation over right), 1/256; 0 where either
// window is too flat to tell.
int pair_gain_q8(const WindowSums& l, const WindowSums& r) {
  if (l.dev < kMinWindowDev || r.dev < kMinWindowDev) return 0;
  return static_cast<int>(div_round(static_cast<std::int64_t>(l.dev) * 256, r.dev));
}

}  // namespace

void PairGainVotes::add(ConstGray8View left, int xl, ConstGray8View right, int xr, int y) {
  const int g = pair_gain_q8(window_sums(left, xl, y), window_sums(right, xr, y));
  if (g < kMinGainQ8 || g > kMaxGainQ8) return;
  ++votes[g - kMinGainQ8];
  ++pairs;
}

int PairGainVotes::median_gain_q8() const {
  if (pairs == 0) return 256;
  int seen = 0;
  for (int i = 0; i < kGainBins; ++i) {
    seen += votes[i];
    if (2 * seen >= pairs) return kMinGainQ8 + i;
  }
  return 256;
}

void PairOffsetVotes::add(ConstGray8View left, int xl, ConstGray8View right, int xr, int y) {
  const WindowSums l = window_sums(left, xl, y), r = window_sums(right, xr, y);
  const int g = pair_gain_q8(l, r);
  // Only the pairs whose own gain agrees with the median (within 1/8).
  if (g == 0 || 8 * std::abs(g - gain_q8) > gain_q8) return;
  // mean_L - gain mean_R in half gray levels.
  const std::int64_t o2 = div_round(
      2 * (static_cast<std::int64_t>(l.sum) * 256 - static_cast<std::int64_t>(r.sum) * gain_q8),
      static_cast<std::int64_t>(kPairWindowArea) * 256);
  if (o2 < -kMaxOffset2 || o2 > kMaxOffset2) return;
  ++votes[o2 + kMaxOffset2];
  ++pairs;
}

GrayMap gray_map_from_pairs(const PairOffsetVotes& s) {
  if (s.pairs < kMinMapPairs) return identity_gray_map();
  int seen = 0, o2 = 0;
  for (int i = 0; i < kOffsetBins; ++i) {
    seen += s.votes[i];
    if (2 * seen >= s.pairs) {
      o2 = i - kMaxOffset2;
      break;
    }
  }
  const std::int64_t offset_q8 = o2 * 128;
  // Within what the estimate resolves on two identical cameras: no map. The
  // change of a mid-gray level decides the offset, not level(0).
  const std::int64_t mid_change_q8 = offset_q8 + 128 * (s.gain_q8 - 256);
  if (std::abs(s.gain_q8 - 256) <= kIdentityGainQ8 &&
      std::llabs(mid_change_q8) <= kIdentityLevels * 256)
    return identity_gray_map();
  return linear_gray_map(s.gain_q8, offset_q8);
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
