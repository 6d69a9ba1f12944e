#include "algo/stereo/dp_select_row.hpp"

#include <algorithm>
#include <cstdlib>

#include "algo/core/disparity.hpp"
#include "algo/stereo/vector_clones.hpp"

namespace petra::match {

namespace {

// a / b truncated toward zero, as the integer division, for |a| < 2^24 and
// b != 0: both are exact floats, and when a / b is not an integer it lies at
// least 1 / |b| from one, more than the quotient's rounding error
// |a / b| 2^-24. In float the loop vectorises (no vector integer division).
inline int div_exact(int a, int b) {
  return static_cast<int>(static_cast<float>(a) / static_cast<float>(b));
}

inline int clamp_value(int v, int lo, int hi) {
  return v < lo ? lo : (v > hi ? hi : v);
}

// The per-pixel lookups at the winning lane (loads at data-dependent
// addresses: the one part that stays scalar).
void gather(const SelectRowInputs& in, const SelectRowScratch& g) {
  const std::int16_t* __restrict k1 = in.k1;
  const std::int16_t* __restrict S = in.S;
  const std::uint16_t* __restrict cost = in.cost;
  const std::int16_t* __restrict rk = in.right_lane + (in.w - 1);
  const std::uint8_t* __restrict rsh = in.right_shadow + (in.lanes - 1);
  std::int32_t* __restrict below = g.below;
  std::int32_t* __restrict above = g.above;
  std::int32_t* __restrict right = g.right;
  std::int32_t* __restrict c = g.cost;
  std::int32_t* __restrict shade = g.shade;
  const int w = in.w, ss = in.s_stride, cs = in.c_stride;
  for (int i = 0; i < w; ++i) {
    const int k = k1[i];
    const std::int16_t* s = S + static_cast<std::ptrdiff_t>(i) * ss + k;
    below[i] = s[-1];
    above[i] = s[1];
    right[i] = rk[k - i];
    c[i] = cost[static_cast<std::ptrdiff_t>(i) * cs + k];
    shade[i] = rsh[i - k];
  }
}

// Every check is evaluated for every pixel and combined without branches:
// which check rejects a pixel is data, and a branch on it mispredicts. The
// first failed check is kept (the order of the checks), counted per row at
// the end by compares summed in vector lanes.
template <bool kConfidence>
PETRA_VECTOR_CLONES [[gnu::noinline]] void decide(const SelectRowInputs& in,
                                                  const SelectRowScratch& g,
                                                  std::int16_t* __restrict out,
                                                  std::uint8_t* __restrict conf,
                                                  std::uint8_t* __restrict why) {
  const std::int16_t* __restrict k1 = in.k1;
  const std::int16_t* __restrict best = in.best;
  const std::int16_t* __restrict second = in.second;
  const std::int16_t* __restrict lo = in.lo;
  const std::int16_t* __restrict hi = in.hi;
  const std::uint8_t* __restrict left_shadow = in.left_shadow;
  const std::int32_t* __restrict below = g.below;
  const std::int32_t* __restrict above = g.above;
  const std::int32_t* __restrict right = g.right;
  const std::int32_t* __restrict cost = g.cost;
  const std::int32_t* __restrict shade = g.shade;
  const int w = in.w, dmin = in.disp_min, width = in.image_width;
  const int xd0 = in.x0 - dmin;  // x - d = xd0 + i - k1
  const int tol = in.lr_tolerance_px, pct = in.uniqueness_pct;
  // Aggregated costs are uint16: a ceiling above that passes them all.
  const int ceiling = static_cast<int>(std::min(in.cost_ceiling, 1L << 20));
  for (int i = 0; i < w; ++i) {
    const int k = k1[i];
    const int d = dmin + k;
    const int xr = xd0 + i - k;
    const int b = best[i], s2 = second[i];
    const bool left = left_shadow[i] == 0;
    const bool in_range = (xr >= 0) & (xr < width);
    const int dr = right[i] - k;
    const bool lr = (dr < 0 ? -dr : dr) <= tol;
    const bool unique = (s2 - b) * 100 >= pct * s2;  // both below 2^15
    const bool cheap = cost[i] <= ceiling;
    const bool lit = !in_range | (shade[i] == 0);
    int r = lit ? kMatched : kShadowRight;
    r = cheap ? r : kCost;
    r = unique ? r : kUniqueness;
    r = lr ? r : kLeftRight;
    r = in_range ? r : kRange;
    r = left ? r : kShadowLeft;
    why[i] = static_cast<std::uint8_t>(r);
    // Sub-pixel: parabola through S at k1 - 1, k1, k1 + 1 when both
    // neighbours are allowed lanes; offset (a - c) / (2 den) px, in 1/16 px,
    // rounded half away from zero. |num| < 2^19: div_exact holds.
    const int sa = below[i], sc = above[i];
    const int den = sa + sc - 2 * b;
    const bool fit = (k > lo[i]) & (k < hi[i]) & (den > 0);  // &: no branch
    const int den_s = fit ? den : 1;
    const int num = 8 * (sa - sc);
    // num + half or num - half by the sign of num, in arithmetic (selects
    // around a division: see below).
    // cppcheck-suppress shiftTooManyBitsSigned ; C++20 defines >> of a negative value
    const int sign = num >> 31;  // 0 or -1
    const int half = den_s >> 1;
    const int off = div_exact(num + ((half ^ sign) - sign), den_s);
    // Selects by multiplication: a select on a division's result lets the
    // compiler move the division into a branch, which stops the vectoriser
    // (a float division may trap, so it is not if-converted).
    const int valid = r == kMatched;
    const int q = d * kDisparityScale + static_cast<int>(fit) * clamp_value(off, -8, 8);
    out[i] = static_cast<std::int16_t>(kInvalidDisparity + valid * (q - kInvalidDisparity));
    if constexpr (kConfidence) {
      // max(s2, 1) in arithmetic; 255 (s2 - b) < 2^23.
      const int margin = div_exact(255 * (s2 - b), s2 + (s2 < 1) * (1 - s2));
      conf[i] = static_cast<std::uint8_t>(valid * clamp_value(margin, 1, 255));
    }
  }
}

}  // namespace

RejectCounts select_row(const SelectRowInputs& in, const SelectRowScratch& scratch,
                        std::int16_t* out, std::uint8_t* conf, std::uint8_t* why) {
  gather(in, scratch);
  if (conf != nullptr)
    decide<true>(in, scratch, out, conf, why);
  else
    decide<false>(in, scratch, out, nullptr, why);
  // Compares summed in vector lanes (a histogram would chain increments of
  // the same counter through memory).
  const std::uint8_t* __restrict y = why;
  int n_range = 0, n_lr = 0, n_unique = 0, n_cost = 0, n_shadow = 0;
  for (int i = 0; i < in.w; ++i) {
    n_range += y[i] == kRange;
    n_lr += y[i] == kLeftRight;
    n_unique += y[i] == kUniqueness;
    n_cost += y[i] == kCost;
    n_shadow += y[i] == kShadowRight;
  }
  return RejectCounts{n_range, n_lr, n_unique, n_cost, n_shadow};
}

}  // namespace petra::match
