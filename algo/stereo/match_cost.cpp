#include "algo/stereo/match_cost.hpp"

#include <algorithm>

#include "algo/core/assert.hpp"
#include "algo/stereo/padded_row.hpp"
#include "algo/stereo/vector_clones.hpp"

namespace petra::match {

static_assert(kRawPad > kRawMax, "padding lanes are selected by a maximum");
static_assert(kRawPad * (2 * kBoxRadiusX + 1) * kWindowRows + kMaxSlantPenalty < 32768,
              "box sums, with the slanted window's penalty, compare as int16");

namespace {

// (dx, dy) of the 16 census neighbours.
constexpr int kCensusOffsets[16][2] = {
    {-1, -1}, {0, -1}, {1, -1}, {-1, 0}, {1, 0}, {-1, 1}, {0, 1}, {1, 1},
    {-2, -2}, {0, -2}, {2, -2}, {-2, 0}, {2, 0}, {-2, 2}, {0, 2}, {2, 2},
};

// Bit count of the two census bytes, popcount(a) + popcount(b), by halving
// steps (no multiply, no table) so the compiler keeps it in byte lanes on
// any target. After two steps each nibble holds at most 4, so the two words
// add without carry and share the last step.
inline std::uint8_t popcount16(std::uint8_t a, std::uint8_t b) {
  a = static_cast<std::uint8_t>(a - ((a >> 1) & 0x55));
  b = static_cast<std::uint8_t>(b - ((b >> 1) & 0x55));
  a = static_cast<std::uint8_t>((a & 0x33) + ((a >> 2) & 0x33));
  b = static_cast<std::uint8_t>((b & 0x33) + ((b >> 2) & 0x33));
  const std::uint8_t s = static_cast<std::uint8_t>(a + b);
  return static_cast<std::uint8_t>((s & 0x0F) + (s >> 4));
}

inline std::uint8_t min8(std::uint8_t a, std::uint8_t b) {
  return a < b ? a : b;
}
inline std::uint8_t max8(std::uint8_t a, std::uint8_t b) {
  return a < b ? b : a;
}

}  // namespace

// One pass over the row: both census bytes of a pixel are built in
// registers (16 compares), instead of 16 read-modify-write passes over the
// two planes.
PETRA_VECTOR_CLONES void census_row(ConstGray8View image, int y, int x0, int n,
                                    std::uint8_t* __restrict inner, std::uint8_t* __restrict outer,
                                    std::uint8_t* rows) {
  const int pw = n + 2 * kCensusRadius;
  for (int r = 0; r < 5; ++r)
    padded_row(image, y - kCensusRadius + r, x0 - kCensusRadius, pw, rows + r * pw);
  const std::uint8_t* __restrict r0 = rows;
  const std::uint8_t* __restrict r1 = rows + pw;
  const std::uint8_t* __restrict r2 = rows + 2 * pw;
  const std::uint8_t* __restrict r3 = rows + 3 * pw;
  const std::uint8_t* __restrict r4 = rows + 4 * pw;
  // Bit b is set when neighbour kCensusOffsets[b] is darker than the centre.
  auto bit = [](std::uint8_t v, std::uint8_t c, int b) {
    return static_cast<std::uint8_t>(v < c ? (1u << b) : 0u);
  };
  for (int i = 0; i < n; ++i) {
    const std::uint8_t c = r2[i + 2];
    inner[i] = static_cast<std::uint8_t>(
        bit(r1[i + 1], c, 0) | bit(r1[i + 2], c, 1) | bit(r1[i + 3], c, 2) | bit(r2[i + 1], c, 3) |
        bit(r2[i + 3], c, 4) | bit(r3[i + 1], c, 5) | bit(r3[i + 2], c, 6) | bit(r3[i + 3], c, 7));
    outer[i] = static_cast<std::uint8_t>(
        bit(r0[i], c, 0) | bit(r0[i + 2], c, 1) | bit(r0[i + 4], c, 2) | bit(r2[i], c, 3) |
        bit(r2[i + 4], c, 4) | bit(r4[i], c, 5) | bit(r4[i + 2], c, 6) | bit(r4[i + 4], c, 7));
  }
}

void gray_row(ConstGray8View image, int y, int x0, int n, std::uint8_t* gray) {
  padded_row(image, y, x0, n, gray);
}

// One column of raw_cost_row: every pointer a restrict parameter, so the
// compiler neither re-reads the inputs after each byte store (a byte store
// may alias anything) nor emits run-time overlap checks per column.
template <int kLanes>
[[gnu::always_inline]] inline void raw_cost_column(
    std::uint8_t ci, std::uint8_t co, std::uint8_t gl, const std::uint8_t* __restrict cri,
    const std::uint8_t* __restrict cro, const std::uint8_t* __restrict gr,
    const std::uint8_t* __restrict ov, const std::uint8_t* __restrict pad,
    std::uint8_t* __restrict out, std::uint16_t* __restrict sum) {
  for (int k = 0; k < kLanes; ++k) {
    const std::uint8_t ad = static_cast<std::uint8_t>(max8(gl, gr[k]) - min8(gl, gr[k]));
    const std::uint8_t c = static_cast<std::uint8_t>(
        popcount16(static_cast<std::uint8_t>(ci ^ cri[k]), static_cast<std::uint8_t>(co ^ cro[k])) +
        (min8(ad, 32) >> 2));
    // Overrides as branch-free selects: padding lanes, then right samples.
    // pad is 0 or kRawPad > kRawMax, so a maximum (one instruction) selects it.
    const std::uint8_t v = max8(ov[k] != 0 ? ov[k] : c, pad[k]);
    sum[k] = static_cast<std::uint16_t>(sum[k] + v - out[k]);
    out[k] = v;
  }
}

template <int kLanes>
[[gnu::always_inline]] inline void neutral_column(const std::uint8_t* __restrict pad,
                                                  std::uint8_t* __restrict out,
                                                  std::uint16_t* __restrict sum) {
  for (int k = 0; k < kLanes; ++k) {
    const std::uint8_t v = pad[k] != 0 ? pad[k] : std::uint8_t{kRawNeutral};
    sum[k] = static_cast<std::uint16_t>(sum[k] + v - out[k]);
    out[k] = v;
  }
}

template <int kLanes>
[[gnu::always_inline]] inline void raw_cost_columns(const RawRowInputs& in, int stride,
                                                    const std::uint8_t* pad, std::uint8_t* raw,
                                                    std::uint16_t* colsum) {
  // Copies of the inputs: the stores below are bytes, which may alias `in`.
  const int n = in.n_left;
  const std::uint8_t* const cil = in.census_inner_left;
  const std::uint8_t* const col = in.census_outer_left;
  const std::uint8_t* const gll = in.gray_left;
  const std::uint8_t* const cir = in.census_inner_right_rev;
  const std::uint8_t* const cor = in.census_outer_right_rev;
  const std::uint8_t* const grr = in.gray_right_rev;
  const std::uint8_t* const ovr = in.override_rev;
  const std::uint8_t* const neu = in.neutral_left;
  for (int i = 0; i < n; ++i) {
    std::uint8_t* out = raw + static_cast<std::ptrdiff_t>(i) * stride;
    std::uint16_t* sum = colsum + static_cast<std::ptrdiff_t>(i) * stride;
    // All `stride` lanes in one vectorised loop (no scalar tail); the lanes
    // beyond k_count keep kRawPad.
    if (neu[i]) {
      neutral_column<kLanes>(pad, out, sum);
      continue;
    }
    const int base = n - 1 - i;
    raw_cost_column<kLanes>(cil[i], col[i], gll[i], cir + base, cor + base, grr + base, ovr + base,
                            pad, out, sum);
  }
}

template <int kLanes>
PETRA_VECTOR_CLONES void raw_cost_row(const RawRowInputs& in, int k_count, std::uint8_t* raw,
                                      std::uint16_t* colsum, int stride_arg) {
  const int stride = kLanes > 0 ? kLanes : stride_arg;
  PETRA_ASSERT(k_count <= stride && stride <= kMaxLanes);
  std::uint8_t pad[kMaxLanes];  // kRawPad on the lanes beyond the range
  for (int k = 0; k < stride; ++k) pad[k] = k < k_count ? 0 : kRawPad;
  if constexpr (kLanes > 0) {
    raw_cost_columns<kLanes>(in, stride, pad, raw, colsum);
  } else {
    // Generic lane count: 16 lanes at a time (stride is a multiple of 16).
    PETRA_ASSERT(stride % 16 == 0);
    for (int k0 = 0; k0 < stride; k0 += 16) {
      RawRowInputs part = in;
      part.census_inner_right_rev += k0;
      part.census_outer_right_rev += k0;
      part.gray_right_rev += k0;
      part.override_rev += k0;
      raw_cost_columns<16>(part, stride, pad + k0, raw + k0, colsum + k0);
    }
  }
}

// Box sums of five columns, each computed directly (a running sum along x
// would chain every column to the previous one's store), into a ring of
// five columns, and the minimum over the five box positions as soon as the
// ring holds them: the ring stays in the first-level cache, where a whole
// row of box sums written then re-read five times did not (one row of
// 64-lane sums is 21 kB). The order of the minimum does not change it.
template <int kLanes>
[[gnu::always_inline]] inline void box_column(const std::uint16_t* __restrict c0, int stride_arg,
                                              std::uint16_t* __restrict cur) {
  const int stride = kLanes > 0 ? kLanes : stride_arg;
  for (int k = 0; k < stride; ++k)
    cur[k] = static_cast<std::uint16_t>(c0[k] + c0[stride + k] + c0[2 * stride + k] +
                                        c0[3 * stride + k] + c0[4 * stride + k]);
}

template <int kLanes>
PETRA_VECTOR_CLONES void box_and_shift_row(const std::uint16_t* colsum, int n, int stride_arg,
                                           std::uint16_t* hs, std::uint16_t* agg) {
  const int stride = kLanes > 0 ? kLanes : stride_arg;
  constexpr int kRing = 2 * kShiftRadiusX + 1;
  for (int j = 0; j < kRing - 1; ++j)
    box_column<kLanes>(colsum + static_cast<std::ptrdiff_t>(j) * stride, stride,
                       hs + static_cast<std::ptrdiff_t>(j) * stride);
  // The sums stay below 2^15 (kAggregatedMax, padding 45 kRawPad), so they
  // are compared as int16: x86-64's baseline SSE2 has a one-instruction
  // signed 16-bit minimum but none for unsigned (GCC emulates it in five).
  const std::int16_t* h = reinterpret_cast<const std::int16_t*>(hs);  // written above: not restrict
  for (int i = 0; i < n; ++i) {
    const int j = i + kRing - 1;  // the column entering the ring
    box_column<kLanes>(colsum + static_cast<std::ptrdiff_t>(j) * stride, stride,
                       hs + static_cast<std::ptrdiff_t>(j % kRing) * stride);
    std::int16_t* __restrict out =
        reinterpret_cast<std::int16_t*>(agg) + static_cast<std::ptrdiff_t>(i) * stride;
    for (int k = 0; k < stride; ++k) {
      const std::int16_t a = lane_min16(h[k], h[stride + k]);
      const std::int16_t b = lane_min16(h[2 * stride + k], h[3 * stride + k]);
      out[k] = lane_min16(lane_min16(a, b), h[4 * stride + k]);
    }
  }
}

// The slanted window's column sums: window row j (top to bottom) read at lane
// k + kSlantLaneOffset[j]. Inner lanes (every row's lane in range) in one
// vectorised loop; the few edge lanes reach past the column and read kRawPad.
template <int kLanes>
PETRA_VECTOR_CLONES void slanted_column_sums(const std::uint8_t* const* rows, int wc,
                                             int stride_arg, std::uint16_t* colsum) {
  const int stride = kLanes > 0 ? kLanes : stride_arg;
  constexpr int kReach = kSlantLaneOffset[kWindowRows - 1];
  static_assert(-kSlantLaneOffset[0] == kReach, "the offsets are symmetric");
  for (int i = 0; i < wc; ++i) {
    const std::ptrdiff_t at = static_cast<std::ptrdiff_t>(i) * stride;
    std::uint16_t* __restrict out = colsum + at;
    static_assert(kWindowRows == 9, "the sum below names the window's nine rows");
    const std::uint8_t* __restrict r0 = rows[0] + at;
    const std::uint8_t* __restrict r1 = rows[1] + at;
    const std::uint8_t* __restrict r2 = rows[2] + at;
    const std::uint8_t* __restrict r3 = rows[3] + at;
    const std::uint8_t* __restrict r4 = rows[4] + at;
    const std::uint8_t* __restrict r5 = rows[5] + at;
    const std::uint8_t* __restrict r6 = rows[6] + at;
    const std::uint8_t* __restrict r7 = rows[7] + at;
    const std::uint8_t* __restrict r8 = rows[8] + at;
    constexpr const int* o = kSlantLaneOffset;
    for (int k = kReach; k < stride - kReach; ++k)
      out[k] = static_cast<std::uint16_t>(r0[k + o[0]] + r1[k + o[1]] + r2[k + o[2]] +
                                          r3[k + o[3]] + r4[k + o[4]] + r5[k + o[5]] +
                                          r6[k + o[6]] + r7[k + o[7]] + r8[k + o[8]]);
    for (int e = 0; e < 2 * kReach; ++e) {
      const int k = e < kReach ? e : stride - 2 * kReach + e;
      unsigned sum = 0;
      for (int j = 0; j < kWindowRows; ++j) {
        const int kk = k + kSlantLaneOffset[j];
        sum += (kk >= 0 && kk < stride) ? rows[j][at + kk] : unsigned{kRawPad};
      }
      out[k] = static_cast<std::uint16_t>(sum);
    }
  }
}

template <int kLanes>
PETRA_VECTOR_CLONES int poorly_matched(const std::uint16_t* agg, int n, int stride_arg,
                                       int only_above, std::uint8_t* poor) {
  const int stride = kLanes > 0 ? kLanes : stride_arg;
  int count = 0;
  for (int i = 0; i < n; ++i) {
    const std::int16_t* __restrict a =
        reinterpret_cast<const std::int16_t*>(agg) + static_cast<std::ptrdiff_t>(i) * stride;
    int best = a[0];  // a plain minimum: the compiler reduces it in vector lanes
    for (int k = 1; k < stride; ++k) best = a[k] < best ? a[k] : best;
    poor[i] = best > only_above;
    count += poor[i];
  }
  return count;
}

template <int kLanes>
PETRA_VECTOR_CLONES void keep_cheaper(std::uint16_t* agg, const std::uint16_t* other, int n,
                                      int stride_arg, int penalty, const std::uint8_t* where) {
  const int stride = kLanes > 0 ? kLanes : stride_arg;
  const std::int16_t pen = static_cast<std::int16_t>(penalty);
  for (int i = 0; i < n; ++i) {
    if (!where[i]) continue;
    std::int16_t* __restrict a =
        reinterpret_cast<std::int16_t*>(agg) + static_cast<std::ptrdiff_t>(i) * stride;
    const std::int16_t* __restrict o =
        reinterpret_cast<const std::int16_t*>(other) + static_cast<std::ptrdiff_t>(i) * stride;
    for (int k = 0; k < stride; ++k) a[k] = lane_min16(a[k], static_cast<std::int16_t>(o[k] + pen));
  }
}

#define PETRA_INSTANTIATE(n)                                                                   \
  template void raw_cost_row<n>(const RawRowInputs&, int, std::uint8_t*, std::uint16_t*, int); \
  template void box_and_shift_row<n>(const std::uint16_t*, int, int, std::uint16_t*,           \
                                     std::uint16_t*);                                          \
  template void slanted_column_sums<n>(const std::uint8_t* const*, int, int, std::uint16_t*);  \
  template int poorly_matched<n>(const std::uint16_t*, int, int, int, std::uint8_t*);          \
  template void keep_cheaper<n>(std::uint16_t*, const std::uint16_t*, int, int, int,           \
                                const std::uint8_t*);
PETRA_MATCH_LANE_COUNTS(PETRA_INSTANTIATE)
#undef PETRA_INSTANTIATE

}  // namespace petra::match
