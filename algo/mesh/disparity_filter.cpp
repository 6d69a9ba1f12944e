#include "algo/mesh/disparity_filter.hpp"

#include <cmath>
#include <cstdint>

namespace petra {

Status validate(const MeanFilterParams& p) {
  if (p.window < 3 || p.window > 31 || p.window % 2 == 0)
    return Error::make(Errc::invalid_argument, "mean filter: window %d must be odd, 3..31",
                       p.window);
  if (!(p.tolerance_px > 0.0) || p.tolerance_px > 1000.0)
    return Error::make(Errc::invalid_argument,
                       "mean filter: tolerance %.3g px must be in (0, 1000]", p.tolerance_px);
  if (p.min_support < 0 || p.min_support > p.window * p.window - 1)
    return Error::make(Errc::invalid_argument, "mean filter: min_support %d must be 0..%d",
                       p.min_support, p.window * p.window - 1);
  return {};
}

std::size_t mean_filter_scratch_bytes(int width) {
  // Column sums (int64) and counts (int32), plus alignment slack.
  return static_cast<std::size_t>(width > 0 ? width : 0) * (sizeof(std::int64_t) + sizeof(int)) +
         16;
}

long count_valid(ConstDisparityMap map) {
  long n = 0;
  for (int y = 0; y < map.q4.height(); ++y) {
    const std::int16_t* row = map.q4.row(y);
    for (int x = 0; x < map.q4.width(); ++x) n += is_valid_disparity(row[x]) ? 1 : 0;
  }
  return n;
}

Result<MeanFilterStats> mean_filter_disparity(ConstDisparityMap in, DisparityMap out,
                                              const MeanFilterParams& params, Arena& scratch) {
  PETRA_TRY(validate(params));
  const int w = in.q4.width(), h = in.q4.height();
  if (out.q4.width() != w || out.q4.height() != h)
    return Error::make(Errc::invalid_argument, "mean filter: output %dx%d, input %dx%d",
                       out.q4.width(), out.q4.height(), w, h);
  if (w > 0 && h > 0 && out.q4.data() == in.q4.data())
    return Error::make(Errc::invalid_argument, "mean filter: output aliases the input");
  out.roi = in.roi;
  MeanFilterStats stats;
  if (w == 0 || h == 0) return stats;

  ArenaScope scope(scratch);
  auto col_sum =
      scratch.allocate<std::int64_t>(static_cast<std::size_t>(w), "mean filter column sums");
  if (!col_sum) return col_sum.error();
  auto col_cnt = scratch.allocate<int>(static_cast<std::size_t>(w), "mean filter column counts");
  if (!col_cnt) return col_cnt.error();
  std::int64_t* sum = col_sum->data();
  int* cnt = col_cnt->data();

  const int r = params.window / 2;
  const std::int64_t tol_q4 =
      static_cast<std::int64_t>(std::llround(params.tolerance_px * kDisparityScale));
  auto add_row = [&](int y, int sign) {
    const std::int16_t* row = in.q4.row(y);
    for (int x = 0; x < w; ++x)
      if (is_valid_disparity(row[x])) {
        sum[x] += sign * row[x];
        cnt[x] += sign;
      }
  };
  for (int y = 0; y < r && y < h; ++y) add_row(y, +1);

  for (int y = 0; y < h; ++y) {
    // Column sums over rows [y - r, y + r] clipped to the map.
    if (y + r < h) add_row(y + r, +1);
    if (y - r - 1 >= 0) add_row(y - r - 1, -1);
    const std::int16_t* src = in.q4.row(y);
    std::int16_t* dst = out.q4.row(y);
    std::int64_t box_sum = 0;
    long box_cnt = 0;
    for (int x = 0; x < r && x < w; ++x) {
      box_sum += sum[x];
      box_cnt += cnt[x];
    }
    for (int x = 0; x < w; ++x) {
      if (x + r < w) {
        box_sum += sum[x + r];
        box_cnt += cnt[x + r];
      }
      if (x - r - 1 >= 0) {
        box_sum -= sum[x - r - 1];
        box_cnt -= cnt[x - r - 1];
      }
      const std::int16_t d = src[x];
      if (!is_valid_disparity(d)) {
        dst[x] = kInvalidDisparity;
        continue;
      }
      ++stats.before;
      const std::int64_t n = box_cnt - 1;  // neighbours only
      const std::int64_t s = box_sum - d;
      if (n < params.min_support || n == 0) {
        dst[x] = kInvalidDisparity;
        ++stats.removed_isolated;
        continue;
      }
      const std::int64_t dev = n * d - s;
      if ((dev < 0 ? -dev : dev) > n * tol_q4) {
        dst[x] = kInvalidDisparity;
        ++stats.removed_spikes;
        continue;
      }
      dst[x] = d;
      ++stats.after;
    }
  }
  return stats;
}

}  // namespace petra
