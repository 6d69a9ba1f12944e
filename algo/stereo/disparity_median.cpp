#include "algo/stereo/disparity_median.hpp"

#include <algorithm>

#include "algo/core/disparity.hpp"
#include "algo/stereo/vector_clones.hpp"

namespace petra {

namespace {

constexpr std::int16_t kLow = -32767;  // below every disparity
constexpr std::int16_t kHigh = 32767;  // above every disparity

inline void sort2(std::int16_t& a, std::int16_t& b) {
  const std::int16_t lo = a < b ? a : b;
  const std::int16_t hi = a < b ? b : a;
  a = lo;
  b = hi;
}

// One output row from three guarded input rows (index 0 and w+1 invalid).
// Every step is branch-free so the compiler runs eight pixels per vector:
// invalid neighbours become alternately kHigh and kLow (the first kHigh),
// which leaves the valid values' (upper) median in the middle of nine; then
// the classic 19-exchange median-of-nine network.
inline std::int16_t pad(std::int16_t x, int& parity, int& valid) {
  const int bad = x == kInvalidDisparity;
  valid += 1 - bad;
  const std::int16_t out = bad ? (parity ? kLow : kHigh) : x;
  parity ^= bad;
  return out;
}

PETRA_VECTOR_CLONES [[gnu::noinline]] void median_row(const std::int16_t* __restrict a,
                                                      const std::int16_t* __restrict b,
                                                      const std::int16_t* __restrict c,
                                                      std::int16_t* __restrict out, int w) {
  for (int i = 0; i < w; ++i) {
    int parity = 0, valid = 0;
    std::int16_t v0 = pad(a[i], parity, valid), v1 = pad(a[i + 1], parity, valid);
    std::int16_t v2 = pad(a[i + 2], parity, valid), v3 = pad(b[i], parity, valid);
    std::int16_t v4 = pad(b[i + 1], parity, valid), v5 = pad(b[i + 2], parity, valid);
    std::int16_t v6 = pad(c[i], parity, valid), v7 = pad(c[i + 1], parity, valid);
    std::int16_t v8 = pad(c[i + 2], parity, valid);
    sort2(v1, v2);
    sort2(v4, v5);
    sort2(v7, v8);
    sort2(v0, v1);
    sort2(v3, v4);
    sort2(v6, v7);
    sort2(v1, v2);
    sort2(v4, v5);
    sort2(v7, v8);
    sort2(v0, v3);
    sort2(v5, v8);
    sort2(v4, v7);
    sort2(v3, v6);
    sort2(v1, v4);
    sort2(v2, v5);
    sort2(v4, v7);
    sort2(v4, v2);
    sort2(v6, v4);
    sort2(v4, v2);
    const std::int16_t centre = b[i + 1];
    out[i] = (centre != kInvalidDisparity && valid >= 5) ? v4 : centre;
  }
}

}  // namespace

Status median3x3_valid(ImageView<std::int16_t> d, std::span<std::int16_t> scratch) {
  const int w = d.width(), h = d.height();
  if (scratch.size() < median3x3_scratch(w))
    return Error::make(Errc::capacity_exceeded, "median: scratch of %zu int16, need %zu",
                       scratch.size(), median3x3_scratch(w));
  if (w == 0 || h == 0) return ok_status();
  const std::size_t gw = static_cast<std::size_t>(w) + 2;
  std::int16_t* rows[3] = {scratch.data(), scratch.data() + gw, scratch.data() + 2 * gw};
  auto load = [&](std::int16_t* dst, int t) {  // guarded copy of row t (or all invalid)
    std::fill(dst, dst + gw, kInvalidDisparity);
    if (t >= 0 && t < h) std::copy(d.row(t), d.row(t) + w, dst + 1);
  };
  // rows: above, current, below, each an unfiltered copy.
  load(rows[0], -1);
  load(rows[1], 0);
  for (int t = 0; t < h; ++t) {
    load(rows[2], t + 1);
    median_row(rows[0], rows[1], rows[2], d.row(t), w);
    std::rotate(rows, rows + 1, rows + 3);
  }
  return ok_status();
}

}  // namespace petra
