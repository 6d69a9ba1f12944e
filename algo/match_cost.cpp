#include "algo/match_cost.hpp"

#include <algorithm>

namespace petra::match {

namespace {

// (dx, dy) of the 16 census neighbours.
constexpr int kCensusOffsets[16][2] = {
    {-1, -1}, {0, -1}, {1, -1}, {-1, 0}, {1, 0}, {-1, 1}, {0, 1}, {1, 1},
    {-2, -2}, {0, -2}, {2, -2}, {-2, 0}, {2, 0}, {-2, 2}, {0, 2}, {2, 2},
};

void padded_row(ConstGray8View img, int y, int x0, int n, std::uint8_t* out) {
  const std::uint8_t* s = img.row(std::clamp(y, 0, img.height() - 1));
  const int last = img.width() - 1;
  // Fast path for the interior; replication only where the span leaves the image.
  if (x0 >= 0 && x0 + n - 1 <= last) {
    std::copy(s + x0, s + x0 + n, out);
    return;
  }
  for (int i = 0; i < n; ++i) out[i] = s[std::clamp(x0 + i, 0, last)];
}

// Bit count of a byte by halving steps (no multiply, no table), so the
// compiler keeps it in byte lanes on any target.
inline std::uint8_t popcount8(std::uint8_t v) {
  v = static_cast<std::uint8_t>(v - ((v >> 1) & 0x55));
  v = static_cast<std::uint8_t>((v & 0x33) + ((v >> 2) & 0x33));
  return static_cast<std::uint8_t>((v + (v >> 4)) & 0x0F);
}

inline std::uint8_t min8(std::uint8_t a, std::uint8_t b) { return a < b ? a : b; }
inline std::uint8_t max8(std::uint8_t a, std::uint8_t b) { return a < b ? b : a; }

}  // namespace

void census_row(ConstGray8View image, int y, int x0, int n, std::uint8_t* __restrict inner,
                std::uint8_t* __restrict outer, std::uint8_t* rows) {
  const int pw = n + 2 * kCensusRadius;
  for (int r = 0; r < 5; ++r) padded_row(image, y - kCensusRadius + r, x0 - kCensusRadius, pw, rows + r * pw);
  const std::uint8_t* __restrict centre = rows + 2 * pw + kCensusRadius;
  for (int i = 0; i < n; ++i) inner[i] = outer[i] = 0;
  for (int b = 0; b < 16; ++b) {
    const std::uint8_t* __restrict nb =
        rows + (2 + kCensusOffsets[b][1]) * pw + kCensusRadius + kCensusOffsets[b][0];
    std::uint8_t* __restrict plane = b < 8 ? inner : outer;
    const std::uint8_t bit = static_cast<std::uint8_t>(1u << (b & 7));
    for (int i = 0; i < n; ++i) plane[i] = static_cast<std::uint8_t>(plane[i] | (nb[i] < centre[i] ? bit : 0));
  }
}

void gray_row(ConstGray8View image, int y, int x0, int n, std::uint8_t* gray) {
  padded_row(image, y, x0, n, gray);
}

void raw_cost_row(const RawRowInputs& in, int k_count, std::uint8_t* raw, std::uint16_t* colsum,
                  int stride) {
  for (int i = 0; i < in.n_left; ++i) {
    std::uint8_t* __restrict out = raw + static_cast<std::ptrdiff_t>(i) * stride;
    std::uint16_t* __restrict sum = colsum + static_cast<std::ptrdiff_t>(i) * stride;
    if (in.neutral_left[i]) {
      for (int k = 0; k < k_count; ++k) {
        sum[k] = static_cast<std::uint16_t>(sum[k] + kRawNeutral - out[k]);
        out[k] = kRawNeutral;
      }
      continue;
    }
    const int base = in.n_left - 1 - i;
    const std::uint8_t ci = in.census_inner_left[i];
    const std::uint8_t co = in.census_outer_left[i];
    const std::uint8_t gl = in.gray_left[i];
    const std::uint8_t* __restrict cri = in.census_inner_right_rev + base;
    const std::uint8_t* __restrict cro = in.census_outer_right_rev + base;
    const std::uint8_t* __restrict gr = in.gray_right_rev + base;
    const std::uint8_t* __restrict ov = in.override_rev + base;
    for (int k = 0; k < k_count; ++k) {
      const std::uint8_t ad = static_cast<std::uint8_t>(max8(gl, gr[k]) - min8(gl, gr[k]));
      const std::uint8_t c = static_cast<std::uint8_t>(
          popcount8(static_cast<std::uint8_t>(ci ^ cri[k])) + popcount8(static_cast<std::uint8_t>(co ^ cro[k])) +
          (min8(ad, 32) >> 2));
      const std::uint8_t v = ov[k] != 0 ? ov[k] : c;
      sum[k] = static_cast<std::uint16_t>(sum[k] + v - out[k]);
      out[k] = v;
    }
  }
}

void box_and_shift_row(const std::uint16_t* colsum, int n, int stride, std::uint16_t* hs,
                       std::uint16_t* agg) {
  const int nh = n + 2 * kShiftRadiusX;
  // Box sums by a running sum along x, vectorised over k.
  for (int k = 0; k < stride; ++k)
    hs[k] = static_cast<std::uint16_t>(colsum[k] + colsum[stride + k] + colsum[2 * stride + k] +
                                       colsum[3 * stride + k] + colsum[4 * stride + k]);
  for (int j = 1; j < nh; ++j) {
    const std::uint16_t* prev = hs + static_cast<std::ptrdiff_t>(j - 1) * stride;
    const std::uint16_t* add = colsum + static_cast<std::ptrdiff_t>(j + 4) * stride;
    const std::uint16_t* sub = colsum + static_cast<std::ptrdiff_t>(j - 1) * stride;
    std::uint16_t* cur = hs + static_cast<std::ptrdiff_t>(j) * stride;
    for (int k = 0; k < stride; ++k) cur[k] = static_cast<std::uint16_t>(prev[k] + add[k] - sub[k]);
  }
  // Minimum over five box positions: min(min(h0,h1), min(h2,h3), h4).
  for (int i = 0; i < n; ++i) {
    const std::uint16_t* h0 = hs + static_cast<std::ptrdiff_t>(i) * stride;
    std::uint16_t* out = agg + static_cast<std::ptrdiff_t>(i) * stride;
    for (int k = 0; k < stride; ++k) {
      const std::uint16_t a = std::min(h0[k], h0[stride + k]);
      const std::uint16_t b = std::min(h0[2 * stride + k], h0[3 * stride + k]);
      out[k] = std::min(std::min(a, b), h0[4 * stride + k]);
    }
  }
}

}  // namespace petra::match
