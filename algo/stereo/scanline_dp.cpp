#include "algo/stereo/scanline_dp.hpp"

#include <algorithm>

#include "algo/core/assert.hpp"
#include "algo/stereo/match_cost.hpp"
#include "algo/stereo/vector_clones.hpp"

namespace petra::match {

static_assert(2 * (kAggregatedMax + kMaxP2) < kForbiddenCost, "forbidden cells must never win");
static_assert(2 * (kAggregatedMax + 2 * kForbiddenCost + kMaxP2) < 32767, "path costs fit int16");

namespace {

// Beyond the disparity lanes: never the minimum, and guard + P1 stays in int16.
constexpr std::int16_t kGuard = 0x3FFF;

// One step of the recursion, returning min_k of the new row:
//   cur = C + min(prev, prev(k+-1) + P1, mn + P2) - mn,  mn = min_k prev.
template <int kLanes>
inline std::int16_t step(const std::int16_t* __restrict prev, const std::uint16_t* __restrict c,
                         std::int16_t* __restrict cur, int stride_arg, int p1, int p2,
                         std::int16_t mn) {
  const int stride = kLanes > 0 ? kLanes : stride_arg;
  const std::int16_t jump = static_cast<std::int16_t>(mn + p2);
  const std::int16_t pen1 = static_cast<std::int16_t>(p1);
  // v >= 0 (best >= mn), so its minimum is taken as uint16: one instruction
  // per vector (SSE4.1 phminposuw) where the signed one is a shuffle chain,
  // and this minimum is on the critical path from one step to the next.
  std::uint16_t m = kGuard;
  for (int k = 0; k < stride; ++k) {
    const std::int16_t near =
        static_cast<std::int16_t>(lane_min16(prev[k - 1], prev[k + 1]) + pen1);
    const std::int16_t best = lane_min16(lane_min16(prev[k], near), jump);
    const std::int16_t v = static_cast<std::int16_t>(c[k] + best - mn);
    cur[k] = v;
    const std::uint16_t u = static_cast<std::uint16_t>(v);
    m = u < m ? u : m;
  }
  return static_cast<std::int16_t>(m);
}

template <int kLanes>
inline std::int16_t first(const std::uint16_t* __restrict c, std::int16_t* __restrict cur,
                          int stride_arg) {
  const int stride = kLanes > 0 ? kLanes : stride_arg;
  std::int16_t m = kGuard;
  for (int k = 0; k < stride; ++k) {
    cur[k] = static_cast<std::int16_t>(c[k]);
    m = lane_min16(m, cur[k]);
  }
  return m;
}

}  // namespace

template <int kLanes>
PETRA_VECTOR_CLONES void apply_bounds(std::uint16_t* cost, int n, int stride_arg,
                                      const std::int16_t* lo, const std::int16_t* hi, int full_hi) {
  const int stride = kLanes > 0 ? kLanes : stride_arg;
  for (int x = 0; x < n; ++x) {
    const int l = lo[x], h = hi[x];
    if (l <= 0 && h >= full_hi) continue;
    std::uint16_t* __restrict c = cost + static_cast<std::ptrdiff_t>(x) * stride;
    for (int k = 0; k < stride; ++k)
      c[k] = static_cast<std::uint16_t>(c[k] + ((k < l || k > h) ? kForbiddenCost : 0));
  }
}

namespace {

// kRows independent scanlines (same n and stride), each with its forward
// (S = L_fwd) and backward (L_bwd) pass: 2 kRows independent chains advanced
// in one loop. A step waits for the previous row's minimum and for its
// stores to reach the shifted loads of prev(k+-1); the other chains' steps
// fill that latency.
template <int kLanes, int kRows>
[[gnu::always_inline]] inline void run_scanlines(const ScanlineInputs* in, std::int16_t* const* S,
                                                 std::int16_t* const* backward) {
  const int row_lanes = in[0].stride;  // cost rows
  const int lanes_arg = in[0].lanes > 0 ? in[0].lanes : row_lanes;
  const int stride = kLanes > 0 ? kLanes : lanes_arg;  // lanes the DP runs over
  const int sp = path_row_stride(stride);              // path rows
  const int n = in[0].n;
  for (int r = 0; r < kRows; ++r) {
    PETRA_ASSERT(in[r].n == n && in[r].n > 0 && in[r].stride == in[0].stride && in[r].p1 >= 0);
    PETRA_ASSERT(in[r].lanes == in[0].lanes && lanes_arg <= row_lanes);
    PETRA_ASSERT(kLanes == 0 || lanes_arg == kLanes);
  }
  auto cost = [&](int r, int x) { return in[r].cost + static_cast<std::ptrdiff_t>(x) * row_lanes; };
  auto srow = [&](int r, int x) {
    return S[r] + static_cast<std::ptrdiff_t>(x) * sp + kGuardLanes;
  };
  auto brow = [&](int r, int x) {
    return backward[r] + static_cast<std::ptrdiff_t>(x) * sp + kGuardLanes;
  };
  std::int16_t mf[kRows], mb[kRows];
  // Guards of each column are set as the DP reaches it (below): set here in
  // a pass of their own, they were the first touch of every line of S and
  // of the backward rows, stores waiting on the cache in a row.
  for (int r = 0; r < kRows; ++r) {
    srow(r, 0)[-1] = srow(r, 0)[stride] = kGuard;
    brow(r, n - 1)[-1] = brow(r, n - 1)[stride] = kGuard;
    mf[r] = first<kLanes>(cost(r, 0), srow(r, 0), stride);
    mb[r] = first<kLanes>(cost(r, n - 1), brow(r, n - 1), stride);
  }
  // The chains' pointers and penalties in locals and the loop over rows
  // unrolled: through the input structures and a rolled loop, each step
  // spent as many scalar instructions on addresses as vector ones on lanes.
  const std::uint16_t* cst[kRows];
  const std::uint16_t* pen2[kRows];
  std::int16_t* fw[kRows];
  std::int16_t* bw[kRows];
  int pen1[kRows];
  for (int r = 0; r < kRows; ++r) {
    cst[r] = in[r].cost;
    pen2[r] = in[r].p2;
    fw[r] = srow(r, 0);
    bw[r] = brow(r, 0);
    pen1[r] = in[r].p1;
    for (int x = 1; x < n; ++x) PETRA_ASSERT(pen2[r][x] <= kMaxP2);
  }
  for (int t = 1; t < n; ++t) {
    const int xb = n - 1 - t;
    const std::ptrdiff_t sf = static_cast<std::ptrdiff_t>(t) * sp;
    const std::ptrdiff_t sb = static_cast<std::ptrdiff_t>(xb) * sp;
    const std::ptrdiff_t cf = static_cast<std::ptrdiff_t>(t) * row_lanes;
    const std::ptrdiff_t cb = static_cast<std::ptrdiff_t>(xb) * row_lanes;
#pragma GCC unroll 4
    for (int r = 0; r < kRows; ++r) {
      fw[r][sf - 1] = fw[r][sf + stride] = kGuard;
      bw[r][sb - 1] = bw[r][sb + stride] = kGuard;
      mf[r] = step<kLanes>(fw[r] + sf - sp, cst[r] + cf, fw[r] + sf, stride, pen1[r], pen2[r][t],
                           mf[r]);
      mb[r] = step<kLanes>(bw[r] + sb + sp, cst[r] + cb, bw[r] + sb, stride, pen1[r],
                           pen2[r][xb + 1], mb[r]);
    }
  }
  // S = L_fwd + L_bwd, unless the caller adds them as it reads S.
  for (int r = 0; r < kRows; ++r) {
    if (!in[r].sum_paths) continue;
    for (int x = 0; x < n; ++x) {
      std::int16_t* __restrict s = srow(r, x);
      const std::int16_t* __restrict b = brow(r, x);
      for (int k = 0; k < stride; ++k) s[k] = static_cast<std::int16_t>(s[k] + b[k]);
    }
  }
}

// Which vector width runs the DP. It is latency-bound: each step waits for
// the previous row's minimum and for the stores of prev to reach the
// shifted loads prev(k+-1). 512-bit vectors measured faster than 256-bit
// ones on an Intel Xeon (160x160 ROI, 42 disparities: the whole matcher 1.86
// against 1.95 ms) and slower on an AMD EPYC, whose AVX-512 splits each
// 512-bit operation in two; so the 512-bit copy runs on Intel CPUs only.
// The copies compute the same integers: outputs are identical.
#if PETRA_HAVE_VECTOR_CLONES
enum class DpCopy { baseline, avx2, avx512 };

DpCopy dp_copy() {
  static const DpCopy copy = [] {
    if (intel_avx512()) return DpCopy::avx512;
    if (__builtin_cpu_supports("x86-64-v3")) return DpCopy::avx2;
    return DpCopy::baseline;
  }();
  return copy;
}

template <int kLanes, int kRows>
[[gnu::target("arch=x86-64-v4")]] void run_avx512(const ScanlineInputs* in, std::int16_t* const* S,
                                                  std::int16_t* const* backward) {
  run_scanlines<kLanes, kRows>(in, S, backward);
}
template <int kLanes, int kRows>
[[gnu::target("arch=x86-64-v3")]] void run_avx2(const ScanlineInputs* in, std::int16_t* const* S,
                                                std::int16_t* const* backward) {
  run_scanlines<kLanes, kRows>(in, S, backward);
}
template <int kLanes, int kRows>
void run_baseline(const ScanlineInputs* in, std::int16_t* const* S, std::int16_t* const* backward) {
  run_scanlines<kLanes, kRows>(in, S, backward);
}

template <int kLanes, int kRows>
void run(const ScanlineInputs* in, std::int16_t* const* S, std::int16_t* const* backward) {
  switch (dp_copy()) {
    case DpCopy::avx512:
      return run_avx512<kLanes, kRows>(in, S, backward);
    case DpCopy::avx2:
      return run_avx2<kLanes, kRows>(in, S, backward);
    case DpCopy::baseline:
      break;
  }
  run_baseline<kLanes, kRows>(in, S, backward);
}
#else
template <int kLanes, int kRows>
void run(const ScanlineInputs* in, std::int16_t* const* S, std::int16_t* const* backward) {
  run_scanlines<kLanes, kRows>(in, S, backward);
}
#endif

}  // namespace

template <int kLanes>
void scanline_dp(const ScanlineInputs& in, std::int16_t* S, std::int16_t* backward) {
  run<kLanes, 1>(&in, &S, &backward);
}

template <int kLanes>
void scanline_dp_pair(const ScanlineInputs& a, std::int16_t* Sa, std::int16_t* backward_a,
                      const ScanlineInputs& b, std::int16_t* Sb, std::int16_t* backward_b) {
  const ScanlineInputs in[2] = {a, b};
  std::int16_t* const S[2] = {Sa, Sb};
  std::int16_t* const back[2] = {backward_a, backward_b};
  run<kLanes, 2>(in, S, back);
}

#define PETRA_INSTANTIATE(n)                                                             \
  template void apply_bounds<n>(std::uint16_t*, int, int, const std::int16_t*,           \
                                const std::int16_t*, int);                               \
  template void scanline_dp<n>(const ScanlineInputs&, std::int16_t*, std::int16_t*);     \
  template void scanline_dp_pair<n>(const ScanlineInputs&, std::int16_t*, std::int16_t*, \
                                    const ScanlineInputs&, std::int16_t*, std::int16_t*);
PETRA_MATCH_LANE_COUNTS(PETRA_INSTANTIATE)
#undef PETRA_INSTANTIATE

}  // namespace petra::match
