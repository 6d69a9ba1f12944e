#include "algo/stereo/match_dp.hpp"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <span>

#include "algo/stereo/disparity_median.hpp"
#include "algo/stereo/dp_select_row.hpp"
#include "algo/stereo/edge_pairs.hpp"
#include "algo/stereo/match_cost.hpp"
#include "algo/stereo/match_photometric.hpp"
#include "algo/stereo/scanline_dp.hpp"
#include "algo/stereo/vector_clones.hpp"

namespace petra {

namespace {

using match::kMarginX;
using match::kRawMax;
using match::kRawNeutral;
using match::kWindowRows;

constexpr int kRightChains = 16;  // at most; see right_winners
constexpr int kLaneBits = 12;     // lanes < match::kMaxLanes = 2^12
// "No winner" in rk: all lane bits set, so it loses every tie of a merge.
constexpr std::int16_t kNoLane = (1 << kLaneBits) - 1;
static_assert(match::kMaxLanes <= kNoLane + 1, "lane keys");
constexpr int kMaxAbsDisparity = 2047;  // Q4 in int16
constexpr int kWindowPixels = (2 * match::kBoxRadiusX + 1) * kWindowRows;
// A textureless ROI has fewer edge pixels than this (and than 1 in 500).
constexpr long kMinEdgePixels = 8;

// Sizes of every buffer of one call, shared by the budget function and the
// allocations so the two cannot drift apart.
struct Layout {
  int w = 0, h = 0, d = 0, dp = 0, band = 0, wc = 0, nrp = 0;

  Layout(int width, int height, int disparities, int lanes = lane_multiple())
      : w(width),
        h(height),
        d(disparities),
        dp((disparities + lanes - 1) / lanes * lanes),
        band(width + disparities - 1),
        wc(width + 2 * kMarginX),
        nrp(wc + dp - 1) {}

  static std::size_t z(long v) { return static_cast<std::size_t>(v); }
  std::size_t edge_maps() const {
    return z(w) * z(h) + z(band) * z(h) + 2 * kArenaSlackPerAllocation;
  }
  std::size_t canny() const { return canny_scratch_bytes(std::max(w, band), h); }
  std::size_t rows() const {
    const std::size_t cells = z(wc) * z(dp);
    std::size_t b = 0;
    b += kWindowRows * cells;                  // raw ring
    b += 2 * cells;                            // column sums
    b += 2 * cells + 2 * z(w) * z(dp) + z(w);  // the slanted box's sums, cost, pixels
    b += 2 * 5 * z(dp);                        // box sums (a ring of five columns)
    // Per row in flight (two): cost, path costs S, backward path costs,
    // bounds, jump penalties.
    b += 2 * (2 * z(w) * z(dp) + 2 * 2 * z(w) * z(match::path_row_stride(dp)) + 3 * 2 * z(w));
    b += 5 * z(nrp + 4) + 4 * z(wc) + 6 * z(nrp);           // census, gray, overrides
    b += 2 * 2 * kRightChains * z(w + dp) + 4 * z(w + dp);  // right winners, keys
    b += 3 * 2 * z(w);                                      // left winners
    b += sizeof(match::EdgePair) * z(w);                    // pairs
    b += 2 * median3x3_scratch(w) + 2 * z(w);               // median rows, shadow row, reasons
    b += z(w + d) + 5 * 4 * z(w);                           // right shadow row, select_row
    b += 44 * kArenaSlackPerAllocation;                     // one per allocation below, with room
    return b + match::edge_row_scratch_bytes(w, band);
  }
  std::size_t total() const { return edge_maps() + std::max(canny(), rows()); }
};

// Lanes of the path costs S: D rounded up to 16 (see match_impl).
constexpr int path_lanes(int disparities) {
  return (disparities + 15) / 16 * 16;
}

template <class T>
Status take(Arena& arena, std::size_t n, const char* what, std::span<T>& out) {
  // Each buffer starts on a 64-byte line (kArenaSlackPerAllocation per allocation in the
  // budget): the lane kernels' rows are whole vectors, and a vector load
  // split across two cache lines costs two accesses (every 512-bit load of
  // an unaligned row does).
  if constexpr (kArenaSlackPerAllocation % sizeof(T) != 0) {  // not a lane row (edge pairs)
    auto r = arena.allocate<T>(n, what);
    if (!r) return r.error();
    out = *r;
    return ok_status();
  }
  auto r = arena.allocate<T>(n + kArenaSlackPerAllocation / sizeof(T), what);
  if (!r) return r.error();
  const std::size_t misalign =
      reinterpret_cast<std::uintptr_t>(r->data()) % kArenaSlackPerAllocation;
  const std::size_t skip = misalign == 0 ? 0 : (kArenaSlackPerAllocation - misalign) / sizeof(T);
  out = r->subspan(skip, n);
  return ok_status();
}

bool shadow_at(const ShadowMask* m, int x, int y) {
  return m != nullptr && m->is_shadow(x, y);
}

// out[i] = `yes` where column x0 + i of row y is shadow, else `no`: one
// pass over the mask row instead of a bounds test per pixel.
void shadow_row(const ShadowMask* m, int y, int x0, int n, std::uint8_t yes, std::uint8_t no,
                std::uint8_t* out) {
  std::fill(out, out + n, no);
  if (m == nullptr || y < m->area.y || y >= m->area.y + m->area.h) return;
  const int a = std::max(x0, m->area.x), b = std::min(x0 + n, m->area.x + m->area.w);
  const std::uint8_t* row = m->mask.row(y - m->area.y) - m->area.x;
  for (int x = a; x < b; ++x) out[x - x0] = row[x] != 0 ? yes : no;
}

Status validate_inputs(const StereoInput& in, Rect roi, const MatchDpParams& p,
                       const MatchBudget& budget) {
  if (in.left.empty() || in.right.empty())
    return Error::make(Errc::invalid_argument, "match_dp: empty image");
  if (in.left.width() != in.right.width() || in.left.height() != in.right.height())
    return Error::make(Errc::invalid_argument, "match_dp: left image is %dx%d but right is %dx%d",
                       in.left.width(), in.left.height(), in.right.width(), in.right.height());
  if (p.disp_min > p.disp_max)
    return Error::make(Errc::invalid_argument, "match_dp: disparity range [%d, %d] is empty",
                       p.disp_min, p.disp_max);
  if (std::abs(p.disp_min) > kMaxAbsDisparity || std::abs(p.disp_max) > kMaxAbsDisparity)
    return Error::make(Errc::out_of_range, "match_dp: disparity range [%d, %d] beyond +-%d px",
                       p.disp_min, p.disp_max, kMaxAbsDisparity);
  const int d = p.disp_max - p.disp_min + 1;
  if (budget.max_width <= 0 || budget.max_height <= 0 || budget.max_disparities <= 0)
    return Error::make(Errc::invalid_argument, "match_dp: budget %dx%d, %d disparities is empty",
                       budget.max_width, budget.max_height, budget.max_disparities);
  if (d > budget.max_disparities)
    return Error::make(Errc::capacity_exceeded,
                       "match_dp: disparity range of %d exceeds the budget of %d", d,
                       budget.max_disparities);
  if (roi.empty())
    return Error::make(Errc::invalid_argument, "match_dp: ROI %dx%d is empty", roi.w, roi.h);
  if (!roi.inside(in.left.width(), in.left.height()))
    return Error::make(Errc::out_of_range, "match_dp: ROI (%d,%d %dx%d) is outside the %dx%d image",
                       roi.x, roi.y, roi.w, roi.h, in.left.width(), in.left.height());
  if (roi.w > budget.max_width || roi.h > budget.max_height)
    return Error::make(Errc::capacity_exceeded, "match_dp: ROI %dx%d exceeds the budget of %dx%d",
                       roi.w, roi.h, budget.max_width, budget.max_height);
  if (p.p1 < 0 || p.p2 < p.p1 || p.p2 > match::kMaxP2)
    return Error::make(Errc::invalid_argument,
                       "match_dp: penalties P1 %d, P2 %d (need 0 <= P1 <= P2 <= %d)", p.p1, p.p2,
                       match::kMaxP2);
  if (p.edge_zncc_floor_pct < -100 || p.edge_zncc_floor_pct > 100 || p.edge_uniqueness_pct < 0 ||
      p.edge_uniqueness_pct > 100 || p.uniqueness_pct < 0 || p.uniqueness_pct > 100)
    return Error::make(Errc::invalid_argument, "match_dp: a percentage is outside its range");
  if (p.edge_tolerance_px < 0 || p.lr_tolerance_px < 0 || p.max_mean_cost <= 0)
    return Error::make(Errc::invalid_argument,
                       "match_dp: tolerances must be >= 0 and the cost ceiling > 0");
  if (p.slant_penalty < 0 || p.slant_penalty > match::kMaxSlantPenalty)
    return Error::make(Errc::invalid_argument, "match_dp: slant_penalty %d not in 0..%d",
                       p.slant_penalty, match::kMaxSlantPenalty);
  if (p.slant_min_mean_cost < 0 || p.slant_min_mean_cost > match::kRawMax)
    return Error::make(Errc::invalid_argument, "match_dp: slant_min_mean_cost %d not in 0..%d",
                       p.slant_min_mean_cost, match::kRawMax);
  return ok_status();
}

Status validate(const StereoInput& in, Rect roi, const MatchDpParams& p, const MatchBudget& budget,
                const DisparityMap& out, ImageView<std::uint8_t> confidence) {
  PETRA_TRY(validate_inputs(in, roi, p, budget));
  if (out.q4.width() != roi.w || out.q4.height() != roi.h)
    return Error::make(Errc::invalid_argument, "match_dp: output is %dx%d, ROI is %dx%d",
                       out.q4.width(), out.q4.height(), roi.w, roi.h);
  if (!confidence.empty() && (confidence.width() != roi.w || confidence.height() != roi.h))
    return Error::make(Errc::invalid_argument, "match_dp: confidence is %dx%d, ROI is %dx%d",
                       confidence.width(), confidence.height(), roi.w, roi.h);
  return ok_status();
}

// Best lane, its value and the best value more than one lane away, over
// v[0..n). Written as three branch-free reductions the compiler vectorises.
struct Winner {
  int k = 0;
  int best = 0;
  int second = 0;
};

// Lane numbers as data: the reductions below compare them with loaded
// values instead of an induction variable, which keeps them vectorised.
struct LaneNumbers {
  std::uint16_t k[match::kMaxLanes];
  constexpr LaneNumbers() : k() {
    for (int i = 0; i < match::kMaxLanes; ++i) k[i] = static_cast<std::uint16_t>(i);
  }
};
constexpr LaneNumbers kLaneNumbers{};

// The reductions run on the values as uint16 (costs and path costs are never
// negative): an unsigned 16-bit minimum over a vector is one instruction
// (phminposuw in the x86-64-v3 copy, uminv on NEON) where the signed one is
// a chain of shuffles. The SSE2 copy has no unsigned minimum: see the signed
// forms below.
template <class T>
const std::uint16_t* as_unsigned(const T* v) {
  static_assert(sizeof(T) == 2, "16-bit lanes");
  return reinterpret_cast<const std::uint16_t*>(v);
}

// Best lane and its value (the second best is another pass over the lanes:
// second_best, second_best_away_inline).
template <int kLanes, class T>
[[gnu::always_inline]] inline Winner best_lane_inline(const T* v_in, int n_arg) {
  const int n = kLanes > 0 ? kLanes : n_arg;
  const std::uint16_t* __restrict v = as_unsigned(v_in);
  std::uint16_t m = 0xFFFF;
  for (int k = 0; k < n; ++k) m = v[k] < m ? v[k] : m;
  // First lane holding the minimum: the smallest of lane-or-0xFFFF over the
  // hits (a compare, an or-not and a minimum).
  const std::uint16_t* __restrict lane = kLaneNumbers.k;
  std::uint16_t first = 0xFFFF;
  for (int k = 0; k < n; ++k) {
    const std::uint16_t miss = static_cast<std::uint16_t>(~-(v[k] == m));
    const std::uint16_t c = static_cast<std::uint16_t>(lane[k] | miss);
    first = c < first ? c : first;
  }
  return Winner{first, m, 0};
}

template <int kLanes, class T>
PETRA_VECTOR_CLONES [[gnu::noinline]] Winner best_lane(const T* v, int n) {
  return best_lane_inline<kLanes>(v, n);
}

// Fills w.second: the best value more than one lane away from w.k.
template <int kLanes, class T>
PETRA_VECTOR_CLONES [[gnu::noinline]] void second_best(const T* v_in, int n_arg, Winner& w) {
  const int n = kLanes > 0 ? kLanes : n_arg;
  const std::uint16_t* __restrict v = as_unsigned(v_in);
  const std::uint16_t* __restrict lane = kLaneNumbers.k;
  const std::uint16_t lo = static_cast<std::uint16_t>(std::max(w.k - 1, 0)),
                      hi = static_cast<std::uint16_t>(w.k + 1);
  std::uint16_t m2 = static_cast<std::uint16_t>(std::numeric_limits<T>::max());
  for (int k = 0; k < n; ++k) {
    const std::uint16_t near = static_cast<std::uint16_t>(-((lane[k] >= lo) & (lane[k] <= hi)));
    const std::uint16_t c = static_cast<std::uint16_t>(v[k] | near);
    m2 = c < m2 ? c : m2;
  }
  w.second = m2;
}

// kNearMask.m[kMaxLanes - k1 + k] is 0xFFFF for |k - k1| <= 1 and 0
// elsewhere: an or with it hides the winner's lanes without a store into
// the row (stores followed by vector loads of the same row stall).
struct NearMask {
  std::uint16_t m[2 * match::kMaxLanes + 1];
  constexpr NearMask() : m() {
    for (int i = 0; i <= 2 * match::kMaxLanes; ++i)
      m[i] = static_cast<std::uint16_t>(
          (i >= match::kMaxLanes - 1 && i <= match::kMaxLanes + 1) ? 0xFFFF : 0);
  }
};
constexpr NearMask kNearMask{};

// The best value more than one lane away from lane k1.
template <int kLanes>
[[gnu::always_inline]] inline int second_best_away_inline(const std::int16_t* v_in, int n_arg,
                                                          int k1) {
  const int n = kLanes > 0 ? kLanes : n_arg;
  const std::uint16_t* __restrict v = as_unsigned(v_in);
  const std::uint16_t* __restrict mask = kNearMask.m + match::kMaxLanes - k1;
  std::uint16_t m = 0x7FFF;
  for (int k = 0; k < n; ++k) {
    const std::uint16_t c = static_cast<std::uint16_t>(v[k] | mask[k]);
    m = c < m ? c : m;
  }
  return m;
}

// Signed forms of the two reductions for the per-pixel pass (path costs are
// int16 >= 0), where unsigned_min_is_native() is false: x86-64's baseline
// SSE2 has signed 16-bit minimum and maximum but emulates unsigned ones.
struct LaneRanks {
  std::int16_t r[match::kMaxLanes];
  constexpr LaneRanks() : r() {
    for (int i = 0; i < match::kMaxLanes; ++i) r[i] = static_cast<std::int16_t>(0x7FFF - i);
  }
};
constexpr LaneRanks kLaneRanks{};

// kNearMaskSigned.m[kMaxLanes - k1 + k] is 0x7FFF for |k - k1| <= 1 and
// -32768 elsewhere: a maximum with it hides the winner's lanes.
struct NearMaskSigned {
  std::int16_t m[2 * match::kMaxLanes + 1];
  constexpr NearMaskSigned() : m() {
    for (int i = 0; i <= 2 * match::kMaxLanes; ++i)
      m[i] = static_cast<std::int16_t>(
          (i >= match::kMaxLanes - 1 && i <= match::kMaxLanes + 1) ? 0x7FFF : -32768);
  }
};
constexpr NearMaskSigned kNearMaskSigned{};

template <int kLanes>
[[gnu::always_inline]] inline Winner best_lane_signed(const std::int16_t* __restrict v, int n_arg) {
  const int n = kLanes > 0 ? kLanes : n_arg;
  std::int16_t m = 0x7FFF;
  for (int k = 0; k < n; ++k) m = v[k] < m ? v[k] : m;
  // First lane holding the minimum: the largest rank 0x7FFF - k of the hits.
  const std::int16_t* __restrict rank = kLaneRanks.r;
  std::int16_t top = 0;
  for (int k = 0; k < n; ++k) {
    const std::int16_t c = static_cast<std::int16_t>(rank[k] & -(v[k] == m));
    top = c > top ? c : top;
  }
  return Winner{0x7FFF - top, m, 0};
}

template <int kLanes>
[[gnu::always_inline]] inline int second_best_away_signed(const std::int16_t* __restrict v,
                                                          int n_arg, int k1) {
  const int n = kLanes > 0 ? kLanes : n_arg;
  const std::int16_t* __restrict mask = kNearMaskSigned.m + match::kMaxLanes - k1;
  std::int16_t m = 0x7FFF;
  for (int k = 0; k < n; ++k) {
    const std::int16_t c = v[k] < mask[k] ? mask[k] : v[k];
    m = c < m ? c : m;
  }
  return m;
}

// Winner lane, its value and the best value more than one lane away, for
// every column of a row of path costs, in one branch-free loop: the
// reductions of successive columns are independent and overlap, where
// interleaved with the per-pixel checks each one's latency was exposed.
// kUnsigned picks the reduction form (unsigned_min_is_native()); both give
// the same result.
// S arrives holding the forward path costs; the first pass adds the
// backward ones (S = forward + backward) as it reads each column, instead of
// the DP's own pass over S (ScanlineInputs::sum_paths).
template <int kLanes, bool kUnsigned>
PETRA_VECTOR_CLONES [[gnu::noinline]] void row_winners(std::int16_t* __restrict S,
                                                       const std::int16_t* __restrict back, int w,
                                                       int row_stride, int lanes_arg,
                                                       std::int16_t* __restrict k1,
                                                       std::int16_t* __restrict best,
                                                       std::int16_t* __restrict second) {
  // Two passes: the second best needs the winner's lane (a reduction, then
  // a load at an address it gives), so in one pass each pixel was a chain of
  // three reductions; apart, the pixels of each pass overlap.
  const int lanes = kLanes > 0 ? kLanes : lanes_arg;
  for (int i = 0; i < w; ++i) {
    std::int16_t* __restrict s = S + static_cast<std::size_t>(i) * row_stride;
    const std::int16_t* __restrict b = back + static_cast<std::size_t>(i) * row_stride;
    for (int k = 0; k < lanes; ++k) s[k] = static_cast<std::int16_t>(s[k] + b[k]);
    Winner win;
    if constexpr (kUnsigned)
      win = best_lane_inline<kLanes>(s, lanes_arg);
    else
      win = best_lane_signed<kLanes>(s, lanes_arg);
    k1[i] = static_cast<std::int16_t>(win.k);
    best[i] = static_cast<std::int16_t>(win.best);
  }
  for (int i = 0; i < w; ++i) {
    const std::int16_t* s = S + static_cast<std::size_t>(i) * row_stride;
    if constexpr (kUnsigned)
      second[i] = static_cast<std::int16_t>(second_best_away_inline<kLanes>(s, lanes_arg, k1[i]));
    else
      second[i] = static_cast<std::int16_t>(second_best_away_signed<kLanes>(s, lanes_arg, k1[i]));
  }
}

template <int kLanes, class T>
Winner winner(const T* v, int n) {
  Winner w = best_lane<kLanes>(v, n);
  second_best<kLanes>(v, n, w);
  return w;
}

bool unique_enough(const Winner& w, int pct) {
  return static_cast<long>(w.second - w.best) * 100 >= static_cast<long>(pct) * w.second;
}

// out[m] = in[n - 1 - m].
PETRA_VECTOR_CLONES [[gnu::noinline]] void reverse_copy(const std::uint8_t* __restrict in, int n,
                                                        std::uint8_t* __restrict out) {
  for (int m = 0; m < n; ++m) out[m] = in[n - 1 - m];
}

// Right-view winners: for right pixel (reversed index m), the lane k of the
// smallest path cost over the left pixels i with m = (w - 1 - i) + k, the
// first (smallest i, so smallest k) on ties. All `lanes` lanes are scanned
// (padding lanes never win), so no scalar tail. Column i updates the running
// minima one entry left of column i - 1's: in one array, each load would
// overlap the previous column's stores at a 2-byte offset, which the CPU
// cannot forward, and wait for them to reach the cache. So column i goes to
// chain i % chains: with 16 chains a chain's consecutive updates are 16
// entries (32 bytes, a whole 256-bit vector) apart and its loads match
// earlier stores exactly. The chains are merged at the end through (cost,
// lane) keys whose minimum keeps the smaller lane on ties: the same first-i
// rule, whatever the number of chains. rmin and rk hold
// kRightChains * (w + lanes) entries, key w + lanes; the lanes of the
// winners end up in rk[0 .. w + lanes - 1).
// How many chains (a power of two, at most kRightChains): 16 where the
// 256-bit argument holds. On an Intel Xeon running the AVX-512 copy, the
// setting and merging of 16 chains cost more than the waits they avoid: 4
// chains measured right_winners at 5.8 % of the 160x160 ROI's time against
// 7.7 % with 16 (2 chains 7.4 %, 1 chain 11 %; perf, docs/log.md).
int right_chains() {
  return intel_avx512() ? 4 : kRightChains;
}

template <int kLanes>
PETRA_VECTOR_CLONES [[gnu::noinline]] void right_winners(const std::int16_t* __restrict S, int w,
                                                         int row_stride, int lanes_arg,
                                                         const std::uint8_t* __restrict skip,
                                                         std::int16_t* __restrict rmin,
                                                         std::int16_t* __restrict rk,
                                                         std::int32_t* __restrict key, int chains) {
  const int lanes = kLanes > 0 ? kLanes : lanes_arg;
  const int len = w + lanes;
  for (int m = 0; m < chains * len; ++m) {
    rmin[m] = 0x7FFF;
    rk[m] = kNoLane;
  }
  for (int i = 0; i < w; ++i) {
    if (skip[i]) continue;
    const std::ptrdiff_t chain = static_cast<std::ptrdiff_t>(i & (chains - 1)) * len;
    const std::int16_t* __restrict s = S + static_cast<std::size_t>(i) * row_stride;
    std::int16_t* __restrict rm = rmin + chain + (w - 1 - i);
    std::int16_t* __restrict rl = rk + chain + (w - 1 - i);
    for (int k = 0; k < lanes; ++k) {
      const bool better = s[k] < rm[k];
      rm[k] = better ? s[k] : rm[k];
      rl[k] = better ? static_cast<std::int16_t>(k) : rl[k];
    }
  }
  // key = cost * 2^12 + lane: costs are below 2^15, lanes below 2^12.
  for (int m = 0; m < len; ++m) key[m] = 0x7FFFFFFF;
  for (int c = 0; c < chains; ++c) {
    const std::int16_t* __restrict cm = rmin + static_cast<std::ptrdiff_t>(c) * len;
    const std::int16_t* __restrict cl = rk + static_cast<std::ptrdiff_t>(c) * len;
    for (int m = 0; m < len; ++m) {
      const std::int32_t k = (static_cast<std::int32_t>(cm[m]) << kLaneBits) | cl[m];
      key[m] = k < key[m] ? k : key[m];
    }
  }
  for (int m = 0; m < len; ++m) {
    const std::int16_t lane = static_cast<std::int16_t>(key[m] & kNoLane);
    rk[m] = lane == kNoLane ? std::int16_t{-1} : lane;
  }
}

}  // namespace

std::size_t match_dp_scratch_bytes(const MatchBudget& b) {
  if (b.max_width <= 0 || b.max_height <= 0 || b.max_disparities <= 0) return 0;
  // The widest lane multiple of any copy: the same budget on every CPU (and
  // so the same flight memory table), never less than the copy that runs.
  return Layout(b.max_width, b.max_height, b.max_disparities, kWidestLaneMultiple).total();
}

Rect right_search_area(Rect roi, int disp_min, int disp_max, int image_width) {
  const int x0 = std::max(0, roi.x - disp_max);
  const int x1 = std::min(image_width - 1, roi.x + roi.w - 1 - disp_min);
  if (roi.empty() || x1 < x0) return Rect{roi.x, roi.y, 0, 0};
  return Rect{x0, roi.y, x1 - x0 + 1, roi.h};
}

namespace {

// Rows go through in pairs: steps 1-3 for two rows, then both DPs at once
// (scanline_dp_pair: the DP is latency-bound, two rows fill each other's
// waits), then steps 4-5 for both. Each row in flight has its own cost,
// bounds, penalties and path costs.
struct RowBuffers {
  std::span<std::uint16_t> agg, p2;
  std::span<std::int16_t> lo, hi, S, back;
};

// The row buffers of one call, taken from the arena once.
struct MatchBuffers {
  std::span<std::uint8_t> ring, census_rows, skip, reasons, cli, clo, gl, cri, cro, gr, ov, t1, t2,
      neutral, rshade, slant_poor;
  std::span<std::uint16_t> colsum, hs, slant_colsum, slant_agg;
  std::span<std::int16_t> rmin, rk, med, wk, wbest, wsecond;
  std::span<std::int32_t> right_keys, gathered;
  std::span<match::EdgePair> pairs;
  RowBuffers rows[2];
  match::SelectRowScratch select_scratch;
};

// In the order and sizes Layout::rows() budgets for.
Status take_buffers(Arena& arena, const Layout& L, int path_stride, MatchBuffers& b) {
  const int w = L.w, D = L.d, Dp = L.dp, wc = L.wc, nrp = L.nrp;
  const std::size_t cells = static_cast<std::size_t>(wc) * Dp;
  PETRA_TRY(take(arena, kWindowRows * cells, "raw cost ring", b.ring));
  PETRA_TRY(take(arena, cells, "column sums", b.colsum));
  PETRA_TRY(take(arena, 5 * static_cast<std::size_t>(Dp), "box sums", b.hs));
  PETRA_TRY(take(arena, cells, "slanted column sums", b.slant_colsum));
  PETRA_TRY(take(arena, static_cast<std::size_t>(w) * Dp, "slanted cost", b.slant_agg));
  PETRA_TRY(take(arena, static_cast<std::size_t>(w), "poorly matched pixels", b.slant_poor));
  for (RowBuffers& r : b.rows) {
    PETRA_TRY(take(arena, static_cast<std::size_t>(w) * Dp, "aggregated cost", r.agg));
    PETRA_TRY(take(arena, static_cast<std::size_t>(w) * path_stride, "path costs", r.S));
    PETRA_TRY(
        take(arena, static_cast<std::size_t>(w) * path_stride, "backward path costs", r.back));
    PETRA_TRY(take(arena, static_cast<std::size_t>(w), "lower bounds", r.lo));
    PETRA_TRY(take(arena, static_cast<std::size_t>(w), "upper bounds", r.hi));
    PETRA_TRY(take(arena, static_cast<std::size_t>(w), "jump penalties", r.p2));
  }

  PETRA_TRY(take(arena, 5 * static_cast<std::size_t>(nrp + 4), "census rows", b.census_rows));
  PETRA_TRY(take(arena, static_cast<std::size_t>(wc), "left census inner", b.cli));
  PETRA_TRY(take(arena, static_cast<std::size_t>(wc), "left census outer", b.clo));
  PETRA_TRY(take(arena, static_cast<std::size_t>(wc), "left gray", b.gl));
  PETRA_TRY(take(arena, static_cast<std::size_t>(wc), "left neutral", b.neutral));
  PETRA_TRY(take(arena, static_cast<std::size_t>(nrp), "right census inner", b.cri));
  PETRA_TRY(take(arena, static_cast<std::size_t>(nrp), "right census outer", b.cro));
  PETRA_TRY(take(arena, static_cast<std::size_t>(nrp), "right gray", b.gr));
  PETRA_TRY(take(arena, static_cast<std::size_t>(nrp), "right override", b.ov));
  PETRA_TRY(take(arena, static_cast<std::size_t>(nrp), "right row 1", b.t1));
  PETRA_TRY(take(arena, static_cast<std::size_t>(nrp), "right row 2", b.t2));

  const std::size_t right_len = static_cast<std::size_t>(kRightChains) * (w + Dp);
  PETRA_TRY(take(arena, right_len, "right winners", b.rmin));
  PETRA_TRY(take(arena, right_len, "right winner lanes", b.rk));
  PETRA_TRY(take(arena, static_cast<std::size_t>(w + Dp), "right winner keys", b.right_keys));
  PETRA_TRY(take(arena, static_cast<std::size_t>(w), "edge pairs", b.pairs));
  PETRA_TRY(take(arena, static_cast<std::size_t>(w), "winner lanes", b.wk));
  PETRA_TRY(take(arena, static_cast<std::size_t>(w), "winner costs", b.wbest));
  PETRA_TRY(take(arena, static_cast<std::size_t>(w), "second best costs", b.wsecond));
  PETRA_TRY(take(arena, median3x3_scratch(w), "median rows", b.med));
  PETRA_TRY(take(arena, static_cast<std::size_t>(w), "shadow row", b.skip));
  PETRA_TRY(take(arena, static_cast<std::size_t>(w), "rejection reasons", b.reasons));
  PETRA_TRY(take(arena, static_cast<std::size_t>(w + D - 1), "right shadow row", b.rshade));
  PETRA_TRY(take(arena, 5 * static_cast<std::size_t>(w), "winner neighbourhoods", b.gathered));
  b.select_scratch.below = b.gathered.data();
  b.select_scratch.above = b.gathered.data() + w;
  b.select_scratch.right = b.gathered.data() + 2 * w;
  b.select_scratch.cost = b.gathered.data() + 3 * w;
  b.select_scratch.shade = b.gathered.data() + 4 * w;
  return ok_status();
}

// What every row of one call shares: inputs, sizes and the tables derived
// from the parameters once.
struct MatchContext {
  const StereoInput& in;
  const Rect roi, band;
  const MatchDpParams& p;
  int W = 0, H = 0;                           // image
  int w = 0, D = 0, Dp = 0, wc = 0, nrp = 0;  // Layout
  int dmin = 0;
  int Ds = 0, sp = 0;  // path cost lanes and row stride
  std::size_t cells = 0;
  Gray8View el, er;  // edge maps (step 1)
  match::GrayMap gray_map{};
  int xl_first = 0;                    // left column of raw cost column 0
  int xr_hi = 0;                       // right column of reversed index 0
  int nr = 0;                          // reversed indices inside the range
  std::uint16_t p2_of_step[256] = {};  // by |dI|: one division per level, not per pixel
  int tol = 0;
  bool unsigned_min = false;
  int chains = 0;
  long cost_ceiling = 0;
  int zfloor = 0;

  MatchContext(const StereoInput& input, Rect roi_in, Rect band_in, const MatchDpParams& params,
               const Layout& L)
      : in(input), roi(roi_in), band(band_in), p(params) {
    W = in.left.width();
    H = in.left.height();
    w = L.w;
    D = L.d;
    Dp = L.dp;
    wc = L.wc;
    nrp = L.nrp;
    dmin = p.disp_min;
    Ds = path_lanes(D);
    sp = match::path_row_stride(Ds);
    cells = static_cast<std::size_t>(wc) * Dp;
    xl_first = roi.x - kMarginX;
    xr_hi = roi.x + w - 1 + kMarginX - dmin;
    nr = wc + D - 1;
    // p2 lowered at intensity edges: P2 * 8 / (8 + |dI|), never below P1 + 1.
    const int p2_floor = std::min(p.p2, p.p1 + 1);
    for (int g = 0; g < 256; ++g)
      p2_of_step[g] = static_cast<std::uint16_t>(std::max(p2_floor, p.p2 * 8 / (8 + g)));
    tol = p.edge_tolerance_px;
    unsigned_min = unsigned_min_is_native();
    chains = right_chains();
    PETRA_ASSERT(chains >= 1 && chains <= kRightChains && (chains & (chains - 1)) == 0);
    cost_ceiling = static_cast<long>(p.max_mean_cost) * kWindowPixels;
    zfloor = p.edge_zncc_floor_pct * match::kZnccOne / 100;
  }
};

// Counts the ROI's shadow pixels; an ROI all in shadow has nothing to match.
Status count_left_shadow(const StereoInput& in, Rect roi, MatchDpStats& st) {
  st.roi_pixels = roi.area();
  if (in.left_shadow != nullptr)
    for (int y = 0; y < roi.h; ++y)
      for (int x = 0; x < roi.w; ++x)
        st.shadow_left += shadow_at(in.left_shadow, roi.x + x, roi.y + y);
  if (st.shadow_left == st.roi_pixels)
    return Error::make(Errc::degenerate, "match_dp: all %ld pixels of the ROI are shadow",
                       st.roi_pixels);
  return ok_status();
}

// Step 1: Canny in both views (the right one only for the edge
// constraint); a textureless ROI is refused here.
Status find_edges(MatchContext& c, Arena& arena, MatchDpStats& st) {
  const int w = c.w, h = c.roi.h;
  std::span<std::uint8_t> edges_left, edges_right;
  PETRA_TRY(take(arena, static_cast<std::size_t>(w) * h, "left edge map", edges_left));
  PETRA_TRY(take(arena, static_cast<std::size_t>(c.band.w) * h, "right edge map", edges_right));
  c.el = Gray8View::over(edges_left, w, h);
  c.er = Gray8View::over(edges_right, c.band.w, h);
  {
    auto s = canny(c.in.left, c.roi, c.p.canny, arena, c.el);
    if (!s) return s.error();
    st.left_edges = s->edge_pixels;
  }
  const long need_edges = std::max(kMinEdgePixels, st.roi_pixels / 500);
  if (st.left_edges < need_edges)
    return Error::make(Errc::degenerate,
                       "match_dp: ROI is textureless (%ld edge pixels, need %ld): nothing to match",
                       st.left_edges, need_edges);
  if (c.p.edge_constraint) {
    auto s = canny(c.in.right, c.band, c.p.canny, arena, c.er);
    if (!s) return s.error();
    st.right_edges = s->edge_pixels;
  }
  return ok_status();
}

// Raw cost of image row y into `raw` ([i][k], column i = left x0 - 4 + i).
template <int kLanes>
void raw_row(const MatchContext& c, MatchBuffers& b, int y, std::uint8_t* raw) {
  const StereoInput& in = c.in;
  const int wc = c.wc, nrp = c.nrp, W = c.W, xl_first = c.xl_first, xr_hi = c.xr_hi;
  match::census_row(in.left, y, xl_first, wc, b.cli.data(), b.clo.data(), b.census_rows.data());
  match::gray_row(in.left, y, xl_first, wc, b.gl.data());
  match::census_row(in.right, y, xr_hi - nrp + 1, nrp, b.t1.data(), b.t2.data(),
                    b.census_rows.data());
  reverse_copy(b.t1.data(), nrp, b.cri.data());
  reverse_copy(b.t2.data(), nrp, b.cro.data());
  match::gray_row(in.right, y, xr_hi - nrp + 1, nrp, b.t1.data());
  match::apply_gray_map(c.gray_map, b.t1.data(), nrp, b.t1.data());
  reverse_copy(b.t1.data(), nrp, b.gr.data());
  const int yc = std::clamp(y, 0, c.H - 1);
  // Right samples: kRawMax outside the image or the range, kRawNeutral in
  // shadow (reversed index m is column xr_hi - m).
  shadow_row(in.right_shadow, yc, xr_hi - nrp + 1, nrp, kRawNeutral, 0, b.t1.data());
  reverse_copy(b.t1.data(), nrp, b.ov.data());
  const int m_lo = std::max(0, xr_hi - W + 1), m_hi = std::min(c.nr - 1, xr_hi);  // inside
  std::fill(b.ov.data(), b.ov.data() + std::clamp(m_lo, 0, nrp), std::uint8_t{kRawMax});
  std::fill(b.ov.data() + std::clamp(m_hi + 1, 0, nrp), b.ov.data() + nrp, std::uint8_t{kRawMax});
  // Left pixels outside the image or in shadow carry no information.
  shadow_row(in.left_shadow, yc, xl_first, wc, 1, 0, b.neutral.data());
  std::fill(b.neutral.data(), b.neutral.data() + std::clamp(-xl_first, 0, wc), std::uint8_t{1});
  std::fill(b.neutral.data() + std::clamp(W - xl_first, 0, wc), b.neutral.data() + wc,
            std::uint8_t{1});
  match::RawRowInputs ri{b.cli.data(), b.clo.data(), b.gl.data(),
                         wc,           b.cri.data(), b.cro.data(),
                         b.gr.data(),  b.ov.data(),  b.neutral.data()};
  match::raw_cost_row<kLanes>(ri, c.D, raw, b.colsum.data(), c.Dp);
}

// Keeps, at the front of `pairs`, the edge pairs the dense cost confirms
// from both views; returns how many.
template <int kLanes>
int confirmed_anchors(const MatchContext& c, const RowBuffers& rb, std::span<match::EdgePair> pairs,
                      int n_pairs) {
  const int D = c.D, Dp = c.Dp, w = c.w, dmin = c.dmin, tol = c.tol;
  int n_anchor = 0;
  for (int a = 0; a < n_pairs; ++a) {
    const match::EdgePair e = pairs[static_cast<std::size_t>(a)];
    const int i = e.x_left - c.roi.x;
    const int kp = e.x_left - e.x_right - dmin;
    // All Dp lanes: the padding lanes' cost exceeds every real one, so
    // they win neither the best nor the second best of a real lane.
    const Winner wl = winner<kLanes>(rb.agg.data() + static_cast<std::size_t>(i) * Dp, Dp);
    if (std::abs(wl.k - kp) > tol || !unique_enough(wl, c.p.edge_uniqueness_pct)) continue;
    // Right view: lanes k whose left column base + k lies in the ROI.
    const int base = e.x_right - c.roi.x + dmin;
    const int k_first = std::max(0, -base), k_last = std::min(D - 1, w - 1 - base);
    if (k_first > k_last) continue;
    // First lane of the smallest cost: the minimum of cost * 2^12 + lane
    // (lanes < 2^12), over four interleaved chains (one chain of
    // compare-and-selects waited on itself at every lane).
    const std::uint16_t* diag = rb.agg.data() + static_cast<std::size_t>(base) * Dp;
    const int dstep = Dp + 1;  // next column, next lane
    auto key = [&](int k) {
      return (static_cast<int>(diag[static_cast<std::ptrdiff_t>(k) * dstep]) << kLaneBits) | k;
    };
    int c0 = key(k_first), c1 = c0, c2 = c0, c3 = c0;
    int k = k_first + 1;
    for (; k + 3 <= k_last; k += 4) {
      c0 = std::min(c0, key(k));
      c1 = std::min(c1, key(k + 1));
      c2 = std::min(c2, key(k + 2));
      c3 = std::min(c3, key(k + 3));
    }
    for (; k <= k_last; ++k) c0 = std::min(c0, key(k));
    const int kr = std::min(std::min(c0, c1), std::min(c2, c3)) & kNoLane;
    if (std::abs(kr - kp) > tol) continue;
    pairs[static_cast<std::size_t>(n_anchor++)] = e;
  }
  return n_anchor;
}

// Ordering: between anchors a and b the right match lies strictly between
// their right points; at an anchor, its disparity.
void bounds_from_anchors(const MatchContext& c, std::span<const match::EdgePair> anchors,
                         RowBuffers& rb) {
  const int D = c.D, w = c.w, dmin = c.dmin, tol = c.tol;
  const int n_anchor = static_cast<int>(anchors.size());
  for (int a = 0; a <= n_anchor; ++a) {
    const bool has_prev = a > 0;
    const bool has_next = a < n_anchor;
    const match::EdgePair* pa = has_prev ? &anchors[static_cast<std::size_t>(a - 1)] : nullptr;
    const match::EdgePair* pb = has_next ? &anchors[static_cast<std::size_t>(a)] : nullptr;
    const int i0 = has_prev ? pa->x_left - c.roi.x + 1 : 0;
    const int i1 = has_next ? pb->x_left - c.roi.x : w;  // exclusive
    for (int i = i0; i < i1; ++i) {
      const int x = c.roi.x + i;
      int klo = 0, khi = D - 1;
      if (has_next) klo = std::max(klo, x - pb->x_right + 1 - tol - dmin);
      if (has_prev) khi = std::min(khi, x - pa->x_right - 1 + tol - dmin);
      if (klo <= khi) {
        rb.lo[i] = static_cast<std::int16_t>(klo);
        rb.hi[i] = static_cast<std::int16_t>(khi);
      }
    }
    if (has_next) {
      const int i = pb->x_left - c.roi.x;
      const int k = pb->x_left - pb->x_right - dmin;
      rb.lo[i] = static_cast<std::int16_t>(std::max(0, k - tol));
      rb.hi[i] = static_cast<std::int16_t>(std::min(D - 1, k + tol));
    }
  }
}

match::EdgeRowInputs edge_row_inputs(const MatchContext& c, int t) {
  match::EdgeRowInputs ei;
  ei.left = c.in.left;
  ei.right = c.in.right;
  ei.y = c.roi.y + t;
  ei.left_edges = c.el.row(t);
  ei.left_x0 = c.roi.x;
  ei.left_n = c.w;
  ei.right_edges = c.er.row(t);
  ei.right_x0 = c.band.x;
  ei.right_n = c.band.w;
  ei.disp_min = c.p.disp_min;
  ei.disp_max = c.p.disp_max;
  ei.zncc_floor_q10 = c.zfloor;
  return ei;
}

// Step 0 from correspondences: the gray levels of the edge pairs of every
// kMapRowStep-th row (ZNCC pairs, unchanged by a gain and offset).
constexpr int kMapRowStep = 8;
template <typename Sink>
Status for_each_sampled_pair(const MatchContext& c, std::span<match::EdgePair> pairs, Arena& arena,
                             Sink& sink) {
  for (int t = 0; t < c.roi.h; t += kMapRowStep) {
    auto n = match::match_edge_row(edge_row_inputs(c, t), arena, pairs);
    if (!n) return n.error();
    for (int a = 0; a < *n; ++a) {
      const match::EdgePair e = pairs[static_cast<std::size_t>(a)];
      sink.add(c.in.left, e.x_left, c.in.right, e.x_right, c.roi.y + t);
    }
  }
  return ok_status();
}
Status choose_gray_map(MatchContext& c, std::span<match::EdgePair> pairs, Arena& arena) {
  c.gray_map = match::identity_gray_map();
  if (!c.p.normalise_gray) return ok_status();
  if (!c.p.edge_constraint) {  // no right edges, so no pairs: the areas' statistics
    c.gray_map = match::gray_map_for_roi(c.in.left, c.in.right, c.roi, c.p.disp_min, c.p.disp_max);
    return ok_status();
  }
  match::PairGainVotes votes;
  PETRA_TRY(for_each_sampled_pair(c, pairs, arena, votes));
  match::PairOffsetVotes sums;
  sums.gain_q8 = votes.median_gain_q8();
  PETRA_TRY(for_each_sampled_pair(c, pairs, arena, sums));
  c.gray_map = match::gray_map_from_pairs(sums);
  return ok_status();
}

// Steps 2-3: edge pairs -> anchors -> bounds of row t (lanes k = d - dmin).
template <int kLanes>
Status edge_bounds(const MatchContext& c, MatchBuffers& b, Arena& arena, MatchDpStats& st, int t,
                   RowBuffers& rb) {
  for (int i = 0; i < c.w; ++i) {
    rb.lo[i] = 0;
    rb.hi[i] = static_cast<std::int16_t>(c.D - 1);
  }
  if (!c.p.edge_constraint) return ok_status();
  auto n_pairs = match::match_edge_row(edge_row_inputs(c, t), arena, b.pairs);
  if (!n_pairs) return n_pairs.error();
  st.edge_pairs += *n_pairs;
  const int n_anchor = confirmed_anchors<kLanes>(c, rb, b.pairs, *n_pairs);
  st.anchors += n_anchor;
  bounds_from_anchors(c, b.pairs.first(static_cast<std::size_t>(n_anchor)), rb);
  return ok_status();
}

// The slanted box over the window of row t (window row j, rows t - 4 .. t + 4,
// sits in ring slot (t + j) mod 9), kept where cheaper than the upright one
// at the pixels the upright box matches poorly (match_cost). Only the runs of
// such pixels are summed: pixel i's boxes read sum columns i .. i + 8, so
// runs closer than that share their columns and are taken as one.
template <int kLanes>
void slanted_box(const MatchContext& c, MatchBuffers& b, int t, RowBuffers& rb) {
  const int w = c.w, Dp = c.Dp;
  std::uint8_t* poor = b.slant_poor.data();
  if (match::poorly_matched<kLanes>(rb.agg.data(), w, Dp, c.p.slant_min_mean_cost * kWindowPixels,
                                    poor) == 0)
    return;
  constexpr int kReadWidth = 2 * match::kMarginX;  // sum columns past a pixel's own
  for (int a = 0; a < w;) {
    if (!poor[a]) {
      ++a;
      continue;
    }
    int e = a + 1;  // end of the run, gaps of up to kReadWidth pixels bridged
    for (int i = e; i < w && i < e + kReadWidth; ++i)
      if (poor[i]) e = i + 1;
    const std::uint8_t* rows[kWindowRows];
    const std::size_t at = static_cast<std::size_t>(a) * Dp;
    for (int j = 0; j < kWindowRows; ++j)
      rows[j] = b.ring.data() + static_cast<std::size_t>((t + j) % kWindowRows) * c.cells + at;
    match::slanted_column_sums<kLanes>(rows, e - a + kReadWidth, Dp, b.slant_colsum.data() + at);
    match::box_and_shift_row<kLanes>(b.slant_colsum.data() + at, e - a, Dp, b.hs.data(),
                                     b.slant_agg.data() + at);
    a = e;
  }
  match::keep_cheaper<kLanes>(rb.agg.data(), b.slant_agg.data(), w, Dp, c.p.slant_penalty, poor);
}

// Steps 1-3 for row t: its window of raw costs, aggregated and bounded,
// and its jump penalties, ready for the DP.
template <int kLanes>
Status prepare_row(const MatchContext& c, MatchBuffers& b, Arena& arena, MatchDpStats& st, int t,
                   RowBuffers& rb) {
  const int y = c.roi.y + t;
  if (t > 0) {  // slide the window down one row
    std::uint8_t* slot = b.ring.data() + static_cast<std::size_t>((t - 1) % kWindowRows) * c.cells;
    raw_row<kLanes>(c, b, y + match::kBoxRadiusY, slot);  // replaces the row leaving the window
  }
  match::box_and_shift_row<kLanes>(b.colsum.data(), c.w, c.Dp, b.hs.data(), rb.agg.data());
  if (c.p.slanted_window) slanted_box<kLanes>(c, b, t, rb);
  PETRA_TRY(edge_bounds<kLanes>(c, b, arena, st, t, rb));

  // Step 3: scanline DP over the aggregated cost.
  const std::uint8_t* img_row = c.in.left.row(y) + c.roi.x;
  for (int i = 1; i < c.w; ++i) {
    const int g = std::abs(img_row[i] - img_row[i - 1]);
    rb.p2[i] = c.p2_of_step[g];
  }
  rb.p2[0] = static_cast<std::uint16_t>(c.p.p2);
  match::apply_bounds<kLanes>(rb.agg.data(), c.w, c.Dp, rb.lo.data(), rb.hi.data(), c.D - 1);
  return ok_status();
}

// Steps 4-5 for row t: select (row_winners completes S = forward + backward
// first: the DP left the sum to it), reject, refine.
template <int kPathLanes>
void finish_row(const MatchContext& c, MatchBuffers& b, MatchDpStats& st, DisparityMap& out,
                ImageView<std::uint8_t> confidence, int t, RowBuffers& rb) {
  const int y = c.roi.y + t, w = c.w, sp = c.sp, Ds = c.Ds;
  std::int16_t* const S = rb.S.data() + match::kGuardLanes;
  const std::int16_t* const back = rb.back.data() + match::kGuardLanes;
  if (c.unsigned_min)
    row_winners<kPathLanes, true>(S, back, w, sp, Ds, b.wk.data(), b.wbest.data(),
                                  b.wsecond.data());
  else
    row_winners<kPathLanes, false>(S, back, w, sp, Ds, b.wk.data(), b.wbest.data(),
                                   b.wsecond.data());

  // Right view winners along the same path costs (reversed index m).
  shadow_row(c.in.left_shadow, y, c.roi.x, w, 1, 0, b.skip.data());
  right_winners<kPathLanes>(S, w, sp, Ds, b.skip.data(), b.rmin.data(), b.rk.data(),
                            b.right_keys.data(), c.chains);
  match::SelectRowInputs si;
  si.w = w;
  si.k1 = b.wk.data();
  si.best = b.wbest.data();
  si.second = b.wsecond.data();
  si.S = rb.S.data() + match::kGuardLanes;
  si.s_stride = sp;
  si.cost = rb.agg.data();
  si.c_stride = c.Dp;
  si.lo = rb.lo.data();
  si.hi = rb.hi.data();
  si.right_lane = b.rk.data();
  si.left_shadow = b.skip.data();
  shadow_row(c.in.right_shadow, y, c.roi.x - c.p.disp_max, w + c.D - 1, 1, 0, b.rshade.data());
  si.right_shadow = b.rshade.data();
  si.lanes = c.D;
  si.x0 = c.roi.x;
  si.disp_min = c.dmin;
  si.image_width = c.W;
  si.lr_tolerance_px = c.p.lr_tolerance_px;
  si.uniqueness_pct = c.p.uniqueness_pct;
  si.cost_ceiling = c.cost_ceiling;
  const match::RejectCounts rc =
      match::select_row(si, b.select_scratch, out.q4.row(t),
                        confidence.empty() ? nullptr : confidence.row(t), b.reasons.data());
  st.rejected_range += rc.range;
  st.rejected_lr += rc.lr;
  st.rejected_uniqueness += rc.uniqueness;
  st.rejected_cost += rc.cost;
  st.rejected_shadow_right += rc.shadow_right;
}

// The whole matcher for one lane count (kLanes = Dp, or 0 for any), so every
// row kernel runs with a compile-time lane count. kPathLanes: the lanes of
// the path costs S (D rounded up to 16, or 0 for any), which may be fewer
// than Dp: the scanline DP runs 256-bit vectors on most CPUs
// (algo/stereo/scanline_dp.cpp), and the lanes of a row rounded up to 32 would only
// be padding to it and to the kernels reading S.
template <int kLanes, int kPathLanes>
PETRA_VECTOR_CLONES Result<MatchDpStats> match_impl(const StereoInput& in, Rect roi,
                                                    const MatchDpParams& p, Arena& arena,
                                                    DisparityMap& out,
                                                    ImageView<std::uint8_t> confidence) {
  const Rect band = right_search_area(roi, p.disp_min, p.disp_max, in.left.width());
  if (band.empty())
    return Error::make(
        Errc::out_of_range,
        "match_dp: disparities [%d, %d] put every match of the ROI outside the right image",
        p.disp_min, p.disp_max);
  const Layout L(roi.w, roi.h, p.disp_max - p.disp_min + 1);
  const int w = L.w, h = L.h, Dp = L.dp;

  ArenaScope scope(arena);
  const std::size_t used_at_entry = arena.used();
  MatchDpStats st;
  PETRA_TRY(count_left_shadow(in, roi, st));

  MatchContext c(in, roi, band, p, L);
  PETRA_ASSERT(kPathLanes == 0 || kPathLanes == c.Ds);
  PETRA_TRY(find_edges(c, arena, st));
  MatchBuffers b;
  PETRA_TRY(take_buffers(arena, L, c.sp, b));
  // Step 0: the right view's gray levels on the left's scale (the cameras'
  // gain and offset), for the intensity term; census does not depend on them.
  PETRA_TRY(choose_gray_map(c, b.pairs, arena));
  st.gray_gain_q8 = c.gray_map.gain_q8;
  st.gray_offset_q8 = c.gray_map.offset_q8;

  // Fill the window for the first ROI row (ring and sums start at zero).
  for (int r = 0; r < kWindowRows; ++r)
    raw_row<kLanes>(c, b, roi.y - match::kBoxRadiusY + r,
                    b.ring.data() + static_cast<std::size_t>(r) * c.cells);
  for (int t = 0; t < h; t += 2) {
    RowBuffers& ra = b.rows[0];
    RowBuffers& rb = b.rows[1];
    PETRA_TRY(prepare_row<kLanes>(c, b, arena, st, t, ra));
    const match::ScanlineInputs sa{ra.agg.data(), w, Dp, ra.p2.data(), p.p1, c.Ds, false};
    if (t + 1 < h) {
      PETRA_TRY(prepare_row<kLanes>(c, b, arena, st, t + 1, rb));
      const match::ScanlineInputs sb{rb.agg.data(), w, Dp, rb.p2.data(), p.p1, c.Ds, false};
      match::scanline_dp_pair<kPathLanes>(sa, ra.S.data(), ra.back.data(), sb, rb.S.data(),
                                          rb.back.data());
    } else {
      match::scanline_dp<kPathLanes>(sa, ra.S.data(), ra.back.data());
    }
    finish_row<kPathLanes>(c, b, st, out, confidence, t, ra);
    if (t + 1 < h) finish_row<kPathLanes>(c, b, st, out, confidence, t + 1, rb);
  }

  if (p.median) PETRA_TRY(median3x3_valid(out.q4, b.med));
  for (int t = 0; t < h; ++t) {
    const std::int16_t* o = out.q4.row(t);
    for (int i = 0; i < w; ++i) st.matched += is_valid_disparity(o[i]);
  }
  out.roi = roi;
  st.scratch_high_water = arena.high_water() - used_at_entry;
  return st;
}

}  // namespace

Result<match::GrayMap> match_dp_gray_map(const StereoInput& in, Rect roi, const MatchDpParams& p,
                                         const MatchBudget& budget, Arena& arena) {
  PETRA_TRY(validate_inputs(in, roi, p, budget));
  const Rect band = right_search_area(roi, p.disp_min, p.disp_max, in.left.width());
  if (band.empty() || !p.normalise_gray) return match::identity_gray_map();
  const Layout L(roi.w, roi.h, p.disp_max - p.disp_min + 1);
  ArenaScope scope(arena);
  MatchDpStats st;
  MatchContext c(in, roi, band, p, L);
  auto edges = find_edges(c, arena, st);
  if (!edges) {  // a textureless ROI has no pairs to measure on
    if (edges.error().code == Errc::degenerate) return match::identity_gray_map();
    return edges.error();
  }
  std::span<match::EdgePair> pairs;
  PETRA_TRY(take(arena, static_cast<std::size_t>(roi.w), "edge pairs", pairs));
  PETRA_TRY(choose_gray_map(c, pairs, arena));
  return c.gray_map;
}

Result<MatchDpStats> match_dp(const StereoInput& in, Rect roi, const MatchDpParams& p,
                              const MatchBudget& budget, Arena& arena, DisparityMap& out,
                              ImageView<std::uint8_t> confidence) {
  PETRA_TRY(validate(in, roi, p, budget, out, confidence));
  const int d = p.disp_max - p.disp_min + 1;
  const bool narrow = path_lanes(d) < Layout(roi.w, roi.h, d).dp;  // S rows 16 lanes short
  switch (Layout(roi.w, roi.h, d).dp) {
#define PETRA_CASE(n)                                                               \
  case n:                                                                           \
    if constexpr ((n) >= 32)                                                        \
      if (narrow) return match_impl<n, (n)-16>(in, roi, p, arena, out, confidence); \
    return match_impl<n, n>(in, roi, p, arena, out, confidence);
    PETRA_MATCH_LANE_COUNTS(PETRA_CASE)
#undef PETRA_CASE
    default:
      return match_impl<0, 0>(in, roi, p, arena, out, confidence);
  }
}

}  // namespace petra
