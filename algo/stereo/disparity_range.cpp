#include "algo/stereo/disparity_range.hpp"

#include <algorithm>
#include <cmath>

#include "algo/stereo/downsample.hpp"

namespace petra {

namespace {

constexpr int kMinCoarseWidth = 32;  // below it the coarse ROI has too little texture

// The pair downsampled by f: the ROI on the left, its right search area on
// the right, in images of the whole pair's size / f.
Status coarse_pair(ConstGray8View left, ConstGray8View right, Rect roi,
                   const RangeSearchParams& params, int f, Arena& scratch, Gray8View& cl,
                   Gray8View& cr) {
  const int W = left.width(), H = left.height();
  const int cw = W / f, ch = H / f;
  auto lbuf = scratch.allocate<std::uint8_t>(static_cast<std::size_t>(cw) * ch, "coarse left");
  if (!lbuf) return lbuf.error();
  auto rbuf = scratch.allocate<std::uint8_t>(static_cast<std::size_t>(cw) * ch, "coarse right");
  if (!rbuf) return rbuf.error();
  cl = Gray8View(lbuf->data(), cw, ch);
  cr = Gray8View(rbuf->data(), cw, ch);
  const Rect area = right_search_area(roi, params.search_min_px, params.search_max_px, W);
  if (area.empty())
    return Error::make(Errc::out_of_range, "disparity range: no right search area for the ROI");
  PETRA_TRY(downsample_box(left, roi, f, cl));
  PETRA_TRY(downsample_box(right, area, f, cr));
  return {};
}

// The scanline DP on the coarse pair over the envelope / f (mp: its
// parameters), into map over the coarse ROI (the blocks wholly inside the ROI).
Status coarse_disparities(Gray8View cl, Gray8View cr, Rect roi, int f,
                          const RangeSearchParams& params, MatchDpParams& mp, Arena& scratch,
                          DisparityMap& map) {
  const int x0 = (roi.x + f - 1) / f, y0 = (roi.y + f - 1) / f;
  const Rect croi{x0, y0, (roi.x + roi.w) / f - x0, (roi.y + roi.h) / f - y0};
  mp.disp_min = params.search_min_px / f;
  mp.disp_max = (params.search_max_px + f - 1) / f;
  const MatchBudget budget{std::max(croi.w, 1), std::max(croi.h, 1), mp.disp_max - mp.disp_min + 1};
  auto q4 = scratch.allocate<std::int16_t>(
      static_cast<std::size_t>(std::max(croi.w, 0)) * static_cast<std::size_t>(std::max(croi.h, 0)),
      "coarse disparity");
  if (!q4) return q4.error();
  map = DisparityMap{ImageView<std::int16_t>(q4->data(), std::max(croi.w, 0), std::max(croi.h, 0)),
                     croi};
  StereoInput in;
  in.left = cl;
  in.right = cr;
  auto stats = match_dp(in, croi, mp, budget, scratch, map);
  if (!stats)
    return Error::make(stats.code(), "disparity range: coarse matching failed (%s)",
                       stats.error().message);
  return {};
}

// Histogram of the coarse disparities over their steps (1/16 px).
struct Histogram {
  std::span<long> bins;
  int steps = 0;
  long total = 0;

  double quantile(double q, const MatchDpParams& mp) const {
    const long target = static_cast<long>(std::ceil(q * static_cast<double>(total)));
    long seen = 0;
    for (int b = 0; b < steps; ++b) {
      seen += bins[static_cast<std::size_t>(b)];
      if (seen >= std::max(target, 1L))
        return static_cast<double>(b) / kDisparityScale + mp.disp_min;
    }
    return static_cast<double>(mp.disp_max);
  }
};

Status coarse_histogram(const DisparityMap& map, const MatchDpParams& mp, Arena& scratch,
                        Histogram& h) {
  const int steps = h.steps = (mp.disp_max - mp.disp_min + 1) * kDisparityScale + 1;
  auto hist = scratch.allocate<long>(static_cast<std::size_t>(steps), "coarse histogram");
  if (!hist) return hist.error();
  h.bins = *hist;
  long total = 0;
  for (int y = 0; y < map.roi.h; ++y)
    for (int x = 0; x < map.roi.w; ++x) {
      const std::int16_t q = map.q4(x, y);
      if (!is_valid_disparity(q)) continue;
      // Matches pinned at the envelope's ends are the matcher's fallback,
      // not a measurement (seen at ROI borders): leave them out.
      if (q <= (mp.disp_min + 1) * kDisparityScale || q >= (mp.disp_max - 1) * kDisparityScale)
        continue;
      const int bin = std::clamp(q - mp.disp_min * kDisparityScale, 0, steps - 1);
      ++h.bins[static_cast<std::size_t>(bin)];
      ++total;
    }
  h.total = total;
  return {};
}

}  // namespace

Status validate(const RangeSearchParams& p) {
  if (p.search_min_px < 0 || p.search_max_px <= p.search_min_px || p.search_max_px > 2000)
    return Error::make(Errc::invalid_argument, "disparity range: envelope %d..%d px invalid",
                       p.search_min_px, p.search_max_px);
  if (p.factor < 1 || p.factor > 8)
    return Error::make(Errc::invalid_argument, "disparity range: factor %d not in 1..8", p.factor);
  if (!(p.low_quantile >= 0 && p.low_quantile < p.high_quantile && p.high_quantile <= 1))
    return Error::make(Errc::invalid_argument, "disparity range: quantiles %.3g..%.3g invalid",
                       p.low_quantile, p.high_quantile);
  if (p.margin_px < 0 || p.min_matches < 1)
    return Error::make(Errc::invalid_argument, "disparity range: margin or min_matches negative");
  return {};
}

int coarse_factor(const RangeSearchParams& p, int roi_width) {
  int f = p.factor;
  while (f > 1 && roi_width / f < kMinCoarseWidth) f /= 2;
  return f;
}

std::size_t disparity_range_scratch_bytes(int width, int height, int max_roi_w, int max_roi_h,
                                          const RangeSearchParams& p) {
  // Every factor the ROI width may select; the smallest gives the largest problem.
  std::size_t worst = 0;
  for (int factor = p.factor; factor >= 1; factor /= 2) {
    const std::size_t cw = static_cast<std::size_t>(width / factor) + 1;
    const std::size_t ch = static_cast<std::size_t>(height / factor) + 1;
    const MatchBudget mb{max_roi_w / factor + 2, max_roi_h / factor + 2,
                         (p.search_max_px - p.search_min_px) / factor + 3};
    const std::size_t bytes = 2 * cw * ch +
                              2 * static_cast<std::size_t>(mb.max_width) * mb.max_height +
                              match_dp_scratch_bytes(mb) + 256;
    worst = std::max(worst, bytes);
    if (factor == 1) break;
  }
  return worst;
}

Result<DisparityRange> find_disparity_range(ConstGray8View left, ConstGray8View right, Rect roi,
                                            const RangeSearchParams& params,
                                            const MatchDpParams& match, Arena& scratch) {
  PETRA_TRY(validate(params));
  const int W = left.width(), H = left.height();
  if (right.width() != W || right.height() != H)
    return Error::make(Errc::invalid_argument, "disparity range: images differ in size");
  if (!roi.inside(W, H))
    return Error::make(Errc::out_of_range, "disparity range: ROI outside the image");
  ArenaScope scope(scratch);
  const int f = coarse_factor(params, roi.w);
  Gray8View cl, cr;
  PETRA_TRY(coarse_pair(left, right, roi, params, f, scratch, cl, cr));
  MatchDpParams mp = match;
  DisparityMap map;
  PETRA_TRY(coarse_disparities(cl, cr, roi, f, params, mp, scratch, map));
  Histogram hist;
  PETRA_TRY(coarse_histogram(map, mp, scratch, hist));
  const long total = hist.total;
  if (total < params.min_matches)
    return Error::make(Errc::no_solution,
                       "disparity range: only %ld coarse matches in the ROI (need %ld): too little "
                       "texture or outside the working envelope",
                       total, params.min_matches);
  DisparityRange out;
  out.factor = f;
  out.coarse_matches = total;
  out.min_px = std::max(
      params.search_min_px,
      static_cast<int>(std::floor(hist.quantile(params.low_quantile, mp) * f)) - params.margin_px);
  out.max_px = std::min(
      params.search_max_px,
      static_cast<int>(std::ceil(hist.quantile(params.high_quantile, mp) * f)) + params.margin_px);
  if (out.max_px <= out.min_px)
    return Error::make(Errc::no_solution, "disparity range: empty range %d..%d", out.min_px,
                       out.max_px);
  return out;
}

}  // namespace petra
