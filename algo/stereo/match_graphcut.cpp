// Graph-cut matcher: budget, validation, per-pixel preparation, automatic
// parameters, the expansion cycles and the output. The expansion move itself
// (graph construction and update) is in match_graphcut_expansion.cpp.
#include <algorithm>
#include <cstdlib>

#include "algo/stereo/match_graphcut.hpp"
#include "algo/stereo/match_photometric.hpp"

namespace petra {

namespace {

constexpr int kAlignSlack = 16;
constexpr int kMaxDisparityMagnitude = 2047;  // Q4 in int16
constexpr std::int32_t kMaxWeight = 1 << 20;  // keeps every capacity sum inside int32

struct Sizes {
  std::size_t roi, strip, disparities;
};

Sizes sizes_of(const GraphCutBudget& b) {
  const auto w = static_cast<std::size_t>(b.max_width);
  const auto h = static_cast<std::size_t>(b.max_height);
  const auto l = static_cast<std::size_t>(b.max_disparities);
  return {w * h, h * (w + l - 1), l};
}

// Deterministic generator for the expansion order (xorshift32).
std::uint32_t next_random(std::uint32_t& state) {
  state ^= state << 13;
  state ^= state >> 17;
  state ^= state << 5;
  return state;
}

MatchBudget dp_budget(const GraphCutBudget& b) {
  return {b.max_width, b.max_height, b.max_disparities};
}

// The images and their shadow masks.
Status check_images(const StereoInput& in) {
  const ConstGray8View& left = in.left;
  const ConstGray8View& right = in.right;
  if (left.empty() || right.empty()) {
    return Error::make(Errc::invalid_argument, "graphcut: empty %s image",
                       left.empty() ? "left" : "right");
  }
  if (right.width() != left.width() || right.height() != left.height()) {
    return Error::make(Errc::invalid_argument,
                       "graphcut: right image %dx%d differs from left %dx%d", right.width(),
                       right.height(), left.width(), left.height());
  }
  const ShadowMask* masks[2] = {in.left_shadow, in.right_shadow};
  for (int k = 0; k < 2; ++k) {
    const ShadowMask* m = masks[k];
    if (m == nullptr) continue;
    if (!m->area.inside(left.width(), left.height()) || m->mask.width() != m->area.w ||
        m->mask.height() != m->area.h) {
      return Error::make(Errc::invalid_argument,
                         "graphcut: %s shadow mask %dx%d for area %d,%d,%d,%d of a %dx%d image",
                         k == 0 ? "left" : "right", m->mask.width(), m->mask.height(), m->area.x,
                         m->area.y, m->area.w, m->area.h, left.width(), left.height());
    }
  }
  return ok_status();
}

// The disparity range, the cycle counts and the energy's weights.
Status check_range_and_weights(const GraphCutParams& params, const GraphCutBudget& budget) {
  if (params.disp_min > params.disp_max || params.disp_min < -kMaxDisparityMagnitude ||
      params.disp_max > kMaxDisparityMagnitude) {
    return Error::make(Errc::invalid_argument, "graphcut: disparity range %d..%d invalid",
                       params.disp_min, params.disp_max);
  }
  const int count = params.disp_max - params.disp_min + 1;
  if (count > budget.max_disparities) {
    return Error::make(Errc::capacity_exceeded, "graphcut: %d disparities above the budget %d",
                       count, budget.max_disparities);
  }
  if (params.max_cycles < 1 || params.max_cycles > kGraphCutMaxCycles) {
    return Error::make(Errc::out_of_range, "graphcut: max_cycles %d outside 1..%d",
                       params.max_cycles, kGraphCutMaxCycles);
  }
  if (params.occlusion_k != kGraphCutAuto &&
      (params.occlusion_k <= 0 || params.occlusion_k > kMaxWeight)) {
    return Error::make(Errc::out_of_range, "graphcut: occlusion_k %d outside 1..%d",
                       params.occlusion_k, kMaxWeight);
  }
  const std::int32_t weights[3] = {params.lambda, params.lambda1, params.lambda2};
  const char* names[3] = {"lambda", "lambda1", "lambda2"};
  for (int k = 0; k < 3; ++k) {
    if (weights[k] != kGraphCutAuto && (weights[k] < 0 || weights[k] > kMaxWeight)) {
      return Error::make(Errc::out_of_range, "graphcut: %s %d outside 0..%d", names[k], weights[k],
                         kMaxWeight);
    }
  }
  return ok_status();
}

// The guided cycles, the start and the data term's parameters.
Status check_start_and_terms(const GraphCutParams& params, Rect roi) {
  if (params.guided_cycles < 0 || params.guided_cycles > kGraphCutMaxCycles) {
    return Error::make(Errc::out_of_range, "graphcut: guided_cycles %d outside 0..%d",
                       params.guided_cycles, kGraphCutMaxCycles);
  }
  if (params.guided_radius < 0 || params.guided_radius > 2 * kMaxDisparityMagnitude) {
    return Error::make(Errc::out_of_range, "graphcut: guided_radius %d outside 0..%d",
                       params.guided_radius, 2 * kMaxDisparityMagnitude);
  }
  if (params.start != GraphCutStart::occluded && params.start != GraphCutStart::block_matching &&
      params.start != GraphCutStart::dp && params.start != GraphCutStart::given) {
    return Error::make(Errc::invalid_argument, "graphcut: start %d unknown",
                       static_cast<int>(params.start));
  }
  if (params.start == GraphCutStart::given &&
      (params.start_map.q4.data() == nullptr || params.start_map.q4.width() != roi.w ||
       params.start_map.q4.height() != roi.h)) {
    return Error::make(Errc::invalid_argument, "graphcut: start_map %dx%d, roi %dx%d",
                       params.start_map.q4.width(), params.start_map.q4.height(), roi.w, roi.h);
  }
  if (params.edge_threshold < 1 || params.edge_threshold > 255) {
    return Error::make(Errc::out_of_range, "graphcut: edge_threshold %d outside 1..255",
                       params.edge_threshold);
  }
  if (params.data_clip < 1 || params.data_clip > 90) {
    return Error::make(Errc::out_of_range, "graphcut: data_clip %d outside 1..90",
                       params.data_clip);
  }
  return ok_status();
}

Error cancelled_error(int cycle, const GraphCutReport& report) {
  return Error::make(Errc::cancelled, "graphcut: cancelled in cycle %d after %d expansions",
                     cycle + 1, report.expansions);
}

}  // namespace

std::size_t GraphCutMatcher::bytes_needed(const GraphCutBudget& budget) {
  if (budget.max_width <= 0 || budget.max_height <= 0 || budget.max_disparities <= 0) return 0;
  const Sizes s = sizes_of(budget);
  std::size_t bytes = 0;
  bytes += s.roi * (sizeof(Sample) + 3 + 4 * sizeof(std::int16_t) + 8 * sizeof(std::int32_t));
  bytes += s.strip * (sizeof(Sample) + 1 + sizeof(std::int16_t) + sizeof(std::int32_t));
  bytes += s.disparities * (sizeof(std::int16_t) + sizeof(std::int32_t));
  bytes += 22 * kAlignSlack;
  bytes += MaxFlow<6>::bytes_needed(static_cast<std::int32_t>(2 * s.roi));
  bytes += match_dp_scratch_bytes(dp_budget(budget));
  return bytes;
}

Status GraphCutMatcher::init(Arena& arena, const GraphCutBudget& budget) {
  if (budget.max_width <= 0 || budget.max_width > 32767 || budget.max_height <= 0 ||
      budget.max_height > 32767) {
    return Error::make(Errc::out_of_range, "graphcut budget: ROI %dx%d outside 1..32767",
                       budget.max_width, budget.max_height);
  }
  if (budget.max_disparities <= 0 || budget.max_disparities > 2 * kMaxDisparityMagnitude + 1) {
    return Error::make(Errc::out_of_range, "graphcut budget: %d disparities outside 1..%d",
                       budget.max_disparities, 2 * kMaxDisparityMagnitude + 1);
  }
  const Sizes s = sizes_of(budget);
  if (2 * s.roi >= (std::size_t{1} << 27)) {
    return Error::make(Errc::out_of_range, "graphcut budget: ROI of %zu pixels above %d", s.roi,
                       (1 << 26) - 1);
  }
#define PETRA_GC_TAKE(member, type, count, what)                  \
  do {                                                            \
    auto taken = arena.allocate<type>((count), "graphcut " what); \
    if (!taken) return taken.error();                             \
    (member) = *taken;                                            \
  } while (false)
  PETRA_GC_TAKE(left_, Sample, s.roi, "left samples");
  PETRA_GC_TAKE(right_, Sample, s.strip, "right samples");
  PETRA_GC_TAKE(left_flags_, std::uint8_t, s.roi, "left flags");
  PETRA_GC_TAKE(right_flags_, std::uint8_t, s.strip, "right flags");
  PETRA_GC_TAKE(label_, std::int16_t, s.roi, "labels");
  PETRA_GC_TAKE(cost_, std::int16_t, s.roi, "costs");
  PETRA_GC_TAKE(alpha_cost_, std::int16_t, s.roi, "alpha costs");
  PETRA_GC_TAKE(alpha_node_, std::int32_t, s.roi, "alpha nodes");
  PETRA_GC_TAKE(old_node_, std::int32_t, s.roi, "old nodes");
  PETRA_GC_TAKE(alpha_slack_, std::int32_t, s.roi, "alpha slack");
  PETRA_GC_TAKE(old_slack_, std::int32_t, s.roi, "old slack");
  PETRA_GC_TAKE(keep_, std::int32_t, s.roi, "keep costs");
  PETRA_GC_TAKE(worklist_, std::int32_t, s.roi, "worklist");
  PETRA_GC_TAKE(alpha_edges_, std::uint8_t, s.roi, "alpha edges");
  PETRA_GC_TAKE(old_edges_, std::uint8_t, s.roi, "old edges");
  PETRA_GC_TAKE(node_pixel_, std::int32_t, 2 * s.roi, "node pixels");
  PETRA_GC_TAKE(right_best_, std::int32_t, s.strip, "right best costs");
  PETRA_GC_TAKE(owner_, std::int16_t, s.strip, "right owners");
  PETRA_GC_TAKE(order_, std::int16_t, s.disparities, "order");
  PETRA_GC_TAKE(last_change_, std::int32_t, s.disparities, "change stamps");
  PETRA_GC_TAKE(guide_, std::int16_t, s.roi, "guide");
  PETRA_GC_TAKE(dp_scratch_, std::byte, match_dp_scratch_bytes(dp_budget(budget)), "dp start");
#undef PETRA_GC_TAKE
  PETRA_TRY(maxflow_.init(arena, static_cast<std::int32_t>(2 * s.roi)));
  budget_ = budget;
  return ok_status();
}

Status GraphCutMatcher::validate(const StereoInput& in, Rect roi, const GraphCutParams& params,
                                 const DisparityMap* out) const {
  if (label_.empty()) return Error::make(Errc::not_ready, "graphcut: match() before init()");
  PETRA_TRY(check_images(in));
  const ConstGray8View& left = in.left;
  if (!roi.inside(left.width(), left.height())) {
    return Error::make(Errc::out_of_range, "graphcut: roi %d,%d,%d,%d outside the %dx%d image",
                       roi.x, roi.y, roi.w, roi.h, left.width(), left.height());
  }
  if (roi.w > budget_.max_width || roi.h > budget_.max_height) {
    return Error::make(Errc::capacity_exceeded, "graphcut: roi %dx%d above the budget %dx%d", roi.w,
                       roi.h, budget_.max_width, budget_.max_height);
  }
  PETRA_TRY(check_range_and_weights(params, budget_));
  PETRA_TRY(check_start_and_terms(params, roi));
  if (out != nullptr && (out->q4.width() != roi.w || out->q4.height() != roi.h)) {
    return Error::make(Errc::invalid_argument, "graphcut: output %dx%d, roi %dx%d", out->q4.width(),
                       out->q4.height(), roi.w, roi.h);
  }
  return ok_status();
}

// The DP's gray-level map of the right view for this ROI and range (in the
// DP start's scratch, free until the start runs); the identity when off.
Result<match::GrayMap> GraphCutMatcher::right_gray_map(const StereoInput& in, Rect roi,
                                                       const GraphCutParams& params) {
  if (!params.normalise_gray) return match::identity_gray_map();
  MatchDpParams dp = params.dp_start;
  dp.disp_min = params.disp_min;
  dp.disp_max = params.disp_max;
  dp.normalise_gray = true;
  Arena scratch(dp_scratch_);
  return match_dp_gray_map(in, roi, dp, dp_budget(budget_), scratch);
}

Status GraphCutMatcher::prepare(const StereoInput& in, Rect roi, const GraphCutParams& params,
                                match::GrayMap* applied) {
  const ConstGray8View& left = in.left;
  const ConstGray8View& right = in.right;
  w_ = roi.w;
  h_ = roi.h;
  roi_x_ = roi.x;
  image_w_ = left.width();
  disp_min_ = params.disp_min;
  num_disp_ = params.disp_max - params.disp_min + 1;
  strip_x0_ = std::max(0, roi.x - params.disp_max);
  const int strip_x1 = std::min(image_w_ - 1, roi.x + roi.w - 1 - params.disp_min);
  strip_w_ = std::max(0, strip_x1 - strip_x0_ + 1);
  clip2_ = 2 * params.data_clip;
  prune_ = params.prune;
  const int threshold = params.edge_threshold;
  // The right view's gray levels on the left's scale (camera gain and offset).
  const match::GrayMap same = match::identity_gray_map();
  auto mapped = right_gray_map(in, roi, params);
  if (!mapped) return mapped.error();
  const match::GrayMap& to_left = *mapped;
  if (applied != nullptr) *applied = to_left;
  for (int y = 0; y < h_; ++y) {
    const int gy = roi.y + y;
    for (int x = 0; x < w_; ++x) {
      const int p = y * w_ + x;
      left_[p] = gc::half_pixel_sample(left, same.level, roi.x + x, gy);
      left_flags_[p] =
          gc::edge_flags(left, same.level, roi.x + x, gy, x + 1 < w_, y + 1 < h_, threshold);
      if (in.left_shadow != nullptr && in.left_shadow->is_shadow(roi.x + x, gy)) {
        left_flags_[p] |= kUnusable;
      }
    }
    for (int xs = 0; xs < strip_w_; ++xs) {
      const int q = y * strip_w_ + xs;
      const int gx = strip_x0_ + xs;
      right_[q] = gc::half_pixel_sample(right, to_left.level, gx, gy);
      right_flags_[q] =
          gc::edge_flags(right, to_left.level, gx, gy, xs + 1 < strip_w_, y + 1 < h_, threshold);
      if (in.right_shadow != nullptr && in.right_shadow->is_shadow(gx, gy)) {
        right_flags_[q] |= kUnusable;
      }
    }
  }
  return ok_status();
}

// K of the original method: the mean over pixels of the k-th smallest data
// cost across the disparity range (pixels whose every assignment is valid; if
// none, pixels with at least k valid ones).
std::int32_t GraphCutMatcher::automatic_k() const {
  const int k = std::min(num_disp_, std::max(3, (num_disp_ + 2) / 4));
  for (int pass = 0; pass < 2; ++pass) {
    std::int64_t sum = 0;
    std::int64_t count = 0;
    for (int y = 0; y < h_; ++y) {
      for (int x = 0; x < w_; ++x) {
        const int p = y * w_ + x;
        if ((left_flags_[p] & kUnusable) != 0) continue;
        int n = 0;
        for (int di = 0; di < num_disp_; ++di) {
          const int qs = roi_x_ + x - (disp_min_ + di) - strip_x0_;
          const int q_image = qs + strip_x0_;
          if (q_image < 0 || q_image >= image_w_) continue;
          const int q = y * strip_w_ + qs;
          if ((right_flags_[q] & kUnusable) != 0) continue;
          order_[n++] = static_cast<std::int16_t>(gc::bt_cost(left_[p], right_[q], clip2_));
        }
        if (pass == 0 ? n < num_disp_ : n < k) continue;
        std::nth_element(order_.begin(), order_.begin() + (k - 1), order_.begin() + n);
        sum += order_[k - 1];
        ++count;
      }
    }
    if (count > 0)
      return static_cast<std::int32_t>(std::max<std::int64_t>(1, (sum + count / 2) / count));
  }
  return 0;
}

void GraphCutMatcher::refresh_pixel(int p, int x, int y) {
  const int lab = label_[p];
  if (lab < 0) return;
  const std::uint8_t* lf = left_flags_.data();
  const std::uint8_t* rf = right_flags_.data();
  const int qx = roi_x_ + x - (disp_min_ + lab);
  const int q = y * strip_w_ + qx - strip_x0_;
  auto weight = [&](int bits, std::uint8_t edge) {
    return (bits & edge) != 0 ? lambda2_ : lambda1_;
  };
  auto usable = [&](int pp, int qq) { return ((lf[pp] | rf[qq]) & kUnusable) == 0; };
  std::int32_t keep = cost_[p] - k_;
  if (x > 0 && label_[p - 1] != lab && qx > 0 && usable(p - 1, q - 1)) {
    keep += weight(lf[p - 1] | rf[q - 1], kEdgeRight);
  }
  if (x + 1 < w_ && label_[p + 1] != lab && qx + 1 < image_w_ && usable(p + 1, q + 1)) {
    keep += weight(lf[p] | rf[q], kEdgeRight);
  }
  if (y > 0 && label_[p - w_] != lab && usable(p - w_, q - strip_w_)) {
    keep += weight(lf[p - w_] | rf[q - strip_w_], kEdgeDown);
  }
  if (y + 1 < h_ && label_[p + w_] != lab && usable(p + w_, q + strip_w_)) {
    keep += weight(lf[p] | rf[q], kEdgeDown);
  }
  keep_[p] = keep;
  old_edges_[p] = static_cast<std::uint8_t>((lf[p] | rf[q]) & (kEdgeRight | kEdgeDown));
}

void GraphCutMatcher::refresh_all() {
  for (int y = 0; y < h_; ++y)
    for (int x = 0; x < w_; ++x) refresh_pixel(y * w_ + x, x, y);
}

// Full energy of the current labelling (also the check of the tracked value).
std::int64_t GraphCutMatcher::energy() const {
  auto valid = [&](int x, int y, int d_index) {
    const int q_image = roi_x_ + x - (disp_min_ + d_index);
    if (q_image < 0 || q_image >= image_w_) return false;
    const int q = y * strip_w_ + q_image - strip_x0_;
    return ((left_flags_[y * w_ + x] | right_flags_[q]) & kUnusable) == 0;
  };
  auto strip_index = [&](int x, int y, int d_index) {
    return y * strip_w_ + roi_x_ + x - (disp_min_ + d_index) - strip_x0_;
  };
  std::int64_t e = 0;
  for (int y = 0; y < h_; ++y) {
    for (int x = 0; x < w_; ++x) {
      const int p = y * w_ + x;
      const int l1 = label_[p];
      if (l1 >= 0) e += cost_[p] - k_;
      for (int dir = 0; dir < 2; ++dir) {
        const int nx = x + (dir == 0 ? 1 : 0);
        const int ny = y + (dir == 0 ? 0 : 1);
        if (nx >= w_ || ny >= h_) continue;
        const int l2 = label_[ny * w_ + nx];
        if (l1 == l2) continue;
        const std::uint8_t bit = dir == 0 ? kEdgeRight : kEdgeDown;
        for (const int l : {l1, l2}) {
          if (l < 0 || !valid(x, y, l) || !valid(nx, ny, l)) continue;
          const bool edge = ((left_flags_[p] | right_flags_[strip_index(x, y, l)]) & bit) != 0;
          e += edge ? lambda2_ : lambda1_;
        }
      }
    }
  }
  return e;
}

Result<std::int32_t> GraphCutMatcher::automatic_occlusion_k(const StereoInput& in, Rect roi,
                                                            const GraphCutParams& params) {
  PETRA_TRY(validate(in, roi, params, nullptr));
  PETRA_TRY(prepare(in, roi, params));
  const std::int32_t k = automatic_k();
  if (k <= 0) {
    return Error::make(Errc::degenerate,
                       "graphcut: no pixel of the roi has %d valid disparities to choose K",
                       std::min(num_disp_, 3));
  }
  return std::min(k, kMaxWeight);
}

Result<GraphCutReport> GraphCutMatcher::match(const StereoInput& in, Rect roi,
                                              const GraphCutParams& params, DisparityMap& out) {
  PETRA_TRY(validate(in, roi, params, &out));
  match::GrayMap applied;
  PETRA_TRY(prepare(in, roi, params, &applied));

  GraphCutReport report;
  report.gray_gain_q8 = applied.gain_q8;
  report.gray_offset_q8 = applied.offset_q8;
  PETRA_TRY(choose_weights(params, report));
  auto started = start_labels(in, roi, params, report);
  if (!started) return started.error();
  std::int64_t e = *started;

  GraphCutStep start;
  start.cycle = -1;
  start.skipped = true;
  start.energy_before = start.energy_after = e;
  notify(params, start);

  std::uint32_t rng = params.seed != 0 ? params.seed : 0x9E3779B9u;
  PETRA_TRY(run_guided_cycles(params, rng, report, e));
  PETRA_TRY(run_full_cycles(params, rng, report, e));
  // The energy tracked from the cut values must be the energy of the result.
  PETRA_ASSERT(energy() == e);
  report.energy = e;
  write_output(roi, out, report);
  return report;
}

// K (automatic unless given) and the Potts weights.
Status GraphCutMatcher::choose_weights(const GraphCutParams& params, GraphCutReport& report) {
  k_ = params.occlusion_k != kGraphCutAuto ? params.occlusion_k : automatic_k();
  if (k_ <= 0) {
    return Error::make(Errc::degenerate,
                       "graphcut: no pixel of the roi has %d valid disparities to choose K",
                       std::min(num_disp_, 3));
  }
  k_ = std::min(k_, kMaxWeight);
  const std::int32_t lambda =
      params.lambda != kGraphCutAuto ? params.lambda : std::max(1, (k_ + 2) / 5);
  lambda1_ = params.lambda1 != kGraphCutAuto ? params.lambda1 : 3 * lambda;
  lambda2_ = params.lambda2 != kGraphCutAuto ? params.lambda2 : lambda;
  report.occlusion_k = k_;
  report.lambda1 = lambda1_;
  report.lambda2 = lambda2_;
  return ok_status();
}

// The starting labelling (report.start says which, after the DP's fallback)
// and the cached terms; returns its energy.
Result<std::int64_t> GraphCutMatcher::start_labels(const StereoInput& in, Rect roi,
                                                   const GraphCutParams& params,
                                                   GraphCutReport& report) {
  const int n = w_ * h_;
  std::int64_t e = 0;  // the all-occluded start
  report.start = params.start;
  if (report.start == GraphCutStart::dp) {
    auto started = dp_labels(in, roi, params);
    if (!started) return started.error();
    if (!*started) report.start = GraphCutStart::block_matching;
  }
  if (report.start == GraphCutStart::given) labels_from_map(params.start_map);
  if (report.start == GraphCutStart::block_matching) block_matching_labels();
  if (report.start != GraphCutStart::occluded) {
    e = energy();
  } else {
    std::fill_n(label_.begin(), n, kOccluded);
    std::fill_n(owner_.begin(), h_ * strip_w_, std::int16_t{-1});
  }
  report.energy_start = e;
  refresh_all();
  std::fill_n(last_change_.begin(), num_disp_, -1);
  return e;
}

void GraphCutMatcher::notify(const GraphCutParams& params, GraphCutStep& step) const {
  if (params.observer.on_expansion == nullptr) return;
  step.labels = std::span<const std::int16_t>(label_.data(), static_cast<std::size_t>(w_ * h_));
  step.width = w_;
  step.height = h_;
  params.observer.on_expansion(params.observer.context, step);
}

// The disparity order of a cycle: a new seeded permutation, or in order.
void GraphCutMatcher::shuffle_order(const GraphCutParams& params, std::uint32_t& rng) {
  for (int i = 0; i < num_disp_; ++i) order_[i] = static_cast<std::int16_t>(i);
  if (!params.random_order) return;
  for (int i = num_disp_ - 1; i > 0; --i) {
    const int j = static_cast<int>(next_random(rng) % static_cast<std::uint32_t>(i + 1));
    std::swap(order_[i], order_[j]);
  }
}

// Guided cycles: moves restricted to the band around the start (their
// results are not optimal over every move, so no skip stamps are set).
Status GraphCutMatcher::run_guided_cycles(const GraphCutParams& params, std::uint32_t& rng,
                                          GraphCutReport& report, std::int64_t& e) {
  const int guided = report.start == GraphCutStart::occluded ? 0 : params.guided_cycles;
  if (guided > 0) std::copy_n(label_.begin(), w_ * h_, guide_.begin());
  for (int cycle = 0; cycle < guided; ++cycle) {
    shuffle_order(params, rng);
    bool decreased = false;
    for (int i = 0; i < num_disp_; ++i) {
      const int alpha = order_[i];
      if (params.cancel != nullptr && params.cancel->cancelled())
        return cancelled_error(cycle, report);
      GraphCutStep step;
      step.cycle = cycle;
      step.guided = true;
      step.disparity = disp_min_ + alpha;
      step.energy_before = e;
      const std::int64_t delta = expand(alpha, report.graph_nodes, params.guided_radius);
      ++report.expansions;
      if (delta < 0) {
        e += delta;
        decreased = true;
        step.applied = true;
      }
      step.energy_after = e;
      notify(params, step);
    }
    ++report.guided_cycles;
    if (!decreased) break;
  }
  return ok_status();
}

// Full cycles over every disparity until one brings no decrease.
Status GraphCutMatcher::run_full_cycles(const GraphCutParams& params, std::uint32_t& rng,
                                        GraphCutReport& report, std::int64_t& e) {
  std::int32_t changes = 0;
  for (int cycle = 0; cycle < params.max_cycles; ++cycle) {
    shuffle_order(params, rng);
    bool decreased = false;
    for (int i = 0; i < num_disp_; ++i) {
      const int alpha = order_[i];
      GraphCutStep step;
      step.cycle = report.guided_cycles + cycle;
      step.disparity = disp_min_ + alpha;
      step.energy_before = e;
      if (params.cancel != nullptr && params.cancel->cancelled()) {
        return cancelled_error(report.guided_cycles + cycle, report);
      }
      if (last_change_[alpha] == changes) {
        // Unchanged since alpha's last expansion, whose result is optimal
        // over every move this one could make.
        step.skipped = true;
        ++report.expansions_skipped;
      } else {
        const std::int64_t delta = expand(alpha, report.graph_nodes);
        ++report.expansions;
        if (delta < 0) {
          e += delta;
          ++changes;
          decreased = true;
          step.applied = true;
        }
        last_change_[alpha] = changes;
      }
      step.energy_after = e;
      notify(params, step);
    }
    ++report.cycles;
    (void)report.cycle_energy.push_back(e);
    if (!decreased) {
      report.converged = true;
      break;
    }
  }
  return ok_status();
}

// The labelling as Q4 disparities, and the pixel counts of the report.
void GraphCutMatcher::write_output(Rect roi, DisparityMap& out, GraphCutReport& report) const {
  out.roi = roi;
  for (int y = 0; y < h_; ++y) {
    std::int16_t* row = out.q4.row(y);
    for (int x = 0; x < w_; ++x) {
      const int p = y * w_ + x;
      const int l = label_[p];
      if (l >= 0) {
        row[x] = static_cast<std::int16_t>((disp_min_ + l) * kDisparityScale);
        ++report.matched_pixels;
      } else {
        row[x] = kInvalidDisparity;
        if ((left_flags_[p] & kUnusable) != 0) {
          ++report.shadow_pixels;
        } else {
          ++report.occluded_pixels;
        }
      }
    }
  }
}

}  // namespace petra
