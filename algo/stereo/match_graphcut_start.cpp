// Starting labellings of the graph-cut matcher (docs/graphcut.md, "Start"):
// the scanline DP matcher's map made unique, or a left-right checked block
// matching of the data term. Each is a valid configuration (every left and
// right pixel in at most one active assignment); the expansions refine it.
#include <algorithm>

#include "algo/stereo/match_graphcut.hpp"

namespace petra {

// Starting labelling: winner-take-all over 5x5 sums of the data cost, kept
// where the left and right winners agree (so it satisfies uniqueness), else
// occluded. Scratch: alpha_cost_ (costs), keep_ (row sums), alpha_slack_
// (window sums), old_slack_ (left best), right_best_ (right best).
void GraphCutMatcher::block_matching_labels() {
  const int n = w_ * h_;
  std::fill_n(old_slack_.begin(), n, INT32_MAX);
  std::fill_n(right_best_.begin(), h_ * strip_w_, INT32_MAX);
  std::fill_n(owner_.begin(), h_ * strip_w_, std::int16_t{-1});
  std::fill_n(label_.begin(), n, kOccluded);
  for (int di = 0; di < num_disp_; ++di) {
    block_cost_sums(disp_min_ + di);
    take_block_winners(di);
  }
  keep_agreeing_winners();
}

// The 5x5 window sums of the data cost at disparity d into alpha_slack_.
void GraphCutMatcher::block_cost_sums(int d) {
  constexpr int kRadius = 2;
  const std::int32_t invalid_cost = clip2_ * clip2_;
  std::int32_t* row_sum = keep_.data();
  std::int32_t* window = alpha_slack_.data();
  for (int y = 0; y < h_; ++y) {
    const int qrow = y * strip_w_ + roi_x_ - d - strip_x0_;
    for (int x = 0; x < w_; ++x) {
      const int p = y * w_ + x;
      const int qx = roi_x_ + x - d;
      const bool valid =
          qx >= 0 && qx < image_w_ && ((left_flags_[p] | right_flags_[qrow + x]) & kUnusable) == 0;
      alpha_cost_[p] = static_cast<std::int16_t>(
          valid ? gc::bt_cost(left_[p], right_[qrow + x], clip2_) : invalid_cost);
    }
    // Horizontal window sums (clamped at the ROI border).
    std::int32_t acc = 0;
    for (int x = 0; x <= std::min(kRadius, w_ - 1); ++x) acc += alpha_cost_[y * w_ + x];
    for (int x = 0; x < w_; ++x) {
      row_sum[y * w_ + x] = acc;
      if (x + kRadius + 1 < w_) acc += alpha_cost_[y * w_ + x + kRadius + 1];
      if (x - kRadius >= 0) acc -= alpha_cost_[y * w_ + x - kRadius];
    }
  }
  for (int x = 0; x < w_; ++x) {
    std::int32_t acc = 0;
    for (int y = 0; y <= std::min(kRadius, h_ - 1); ++y) acc += row_sum[y * w_ + x];
    for (int y = 0; y < h_; ++y) {
      window[y * w_ + x] = acc;
      if (y + kRadius + 1 < h_) acc += row_sum[(y + kRadius + 1) * w_ + x];
      if (y - kRadius >= 0) acc -= row_sum[(y - kRadius) * w_ + x];
    }
  }
}

// The best window sum so far of each left pixel (label_) and of each right
// pixel (owner_), with disparity index di's sums.
void GraphCutMatcher::take_block_winners(int di) {
  const int d = disp_min_ + di;
  const std::int32_t* window = alpha_slack_.data();
  for (int y = 0; y < h_; ++y) {
    for (int x = 0; x < w_; ++x) {
      const int p = y * w_ + x;
      const int qx = roi_x_ + x - d;
      if (qx < 0 || qx >= image_w_) continue;
      const std::int32_t c = window[p];
      if (c < old_slack_[p]) {
        old_slack_[p] = c;
        label_[p] = static_cast<std::int16_t>(di);
      }
      const int q = y * strip_w_ + qx - strip_x0_;
      if (c < right_best_[q]) {
        right_best_[q] = c;
        owner_[q] = static_cast<std::int16_t>(di);
      }
    }
  }
}

// Keep the left winners the right side agrees with; owners become left x.
void GraphCutMatcher::keep_agreeing_winners() {
  for (int y = 0; y < h_; ++y) {
    for (int x = 0; x < w_; ++x) {
      const int p = y * w_ + x;
      const int l = label_[p];
      if (l < 0) continue;
      const int qx = roi_x_ + x - (disp_min_ + l);
      const int q = y * strip_w_ + qx - strip_x0_;
      const bool usable = ((left_flags_[p] | right_flags_[q]) & kUnusable) == 0;
      if (!usable || owner_[q] != l) label_[p] = kOccluded;
    }
  }
  std::fill_n(owner_.begin(), h_ * strip_w_, std::int16_t{-1});
  for (int y = 0; y < h_; ++y) {
    for (int x = 0; x < w_; ++x) {
      const int p = y * w_ + x;
      const int l = label_[p];
      if (l < 0) continue;
      const int q = y * strip_w_ + roi_x_ + x - (disp_min_ + l) - strip_x0_;
      PETRA_ASSERT(owner_[q] < 0);
      owner_[q] = static_cast<std::int16_t>(x);
      cost_[p] = static_cast<std::int16_t>(gc::bt_cost(left_[p], right_[q], clip2_));
    }
  }
}

// Starting labelling from the scanline DP matcher (algo/stereo/match_dp) run on
// the same input (labels_from_map below). False when the DP finds nothing to
// start from (too few edges, all shadow, range beyond its limit); an error
// for bad DP parameters. Scratch: alpha_cost_ (the DP map), dp_scratch_ (the
// DP's arena).
Result<bool> GraphCutMatcher::dp_labels(const StereoInput& in, Rect roi,
                                        const GraphCutParams& params) {
  DisparityMap map{ImageView<std::int16_t>(alpha_cost_.data(), w_, h_), {}};
  MatchDpParams dp = params.dp_start;
  dp.disp_min = params.disp_min;
  dp.disp_max = params.disp_max;
  const MatchBudget dp_budget{budget_.max_width, budget_.max_height, budget_.max_disparities};
  Arena scratch(dp_scratch_);
  auto run = match_dp(in, roi, dp, dp_budget, scratch, map);
  if (!run) {
    const Errc code = run.error().code;
    if (code == Errc::invalid_argument || code == Errc::capacity_exceeded) return run.error();
    return false;
  }
  labels_from_map(map);
  return true;
}

// A map's Q4 disparities rounded to whole pixels; invalid, shadowed or
// out-of-range ones occluded. Where two left pixels claim one right pixel
// (rounding, or the DP's +-1 px consistency tolerance), the cheaper claimant
// keeps it (ties: the first on the row). Scratch: right_best_ (claimant cost
// per strip pixel).
void GraphCutMatcher::labels_from_map(const ConstDisparityMap& map) {
  const int n = w_ * h_;
  std::fill_n(label_.begin(), n, kOccluded);
  std::fill_n(owner_.begin(), h_ * strip_w_, std::int16_t{-1});
  for (int y = 0; y < h_; ++y) {
    const std::int16_t* row = map.q4.row(y);
    for (int x = 0; x < w_; ++x) {
      const std::int16_t v = row[x];
      if (!is_valid_disparity(v)) continue;
      const int d = (v + kDisparityScale / 2) >>
                    kDisparityFracBits;  // nearest whole pixel (arithmetic shift)
      const int di = d - disp_min_;
      const int qx = roi_x_ + x - d;
      if (di < 0 || di >= num_disp_ || qx < 0 || qx >= image_w_) continue;
      const int p = y * w_ + x;
      const int q = y * strip_w_ + qx - strip_x0_;
      if (((left_flags_[p] | right_flags_[q]) & kUnusable) != 0) continue;
      const std::int32_t c = gc::bt_cost(left_[p], right_[q], clip2_);
      const int rival = owner_[q];
      if (rival >= 0) {
        if (right_best_[q] <= c) continue;
        label_[y * w_ + rival] = kOccluded;
      }
      owner_[q] = static_cast<std::int16_t>(x);
      right_best_[q] = c;
      label_[p] = static_cast<std::int16_t>(di);
      cost_[p] = static_cast<std::int16_t>(c);
    }
  }
}

}  // namespace petra
