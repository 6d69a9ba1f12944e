// PETRA_VECTOR_CLONES marks a lane kernel (a loop over disparity lanes the
// compiler vectorises) to be compiled three times on x86-64: for the baseline
// (SSE2), for x86-64-v3 (AVX2, 256-bit vectors) and for x86-64-v4 (AVX-512,
// 512-bit vectors), the copy being chosen once at program load from the CPU's
// features (GCC function multiversioning: no heap, no intrinsics, same
// integer arithmetic, so bit-identical outputs).
// Elsewhere (aarch64 flight build: NEON) it is empty and the kernel is
// compiled once for the target. Define PETRA_NO_VECTOR_CLONES to measure the
// baseline copy alone.
#pragma once

#include <cstdint>

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && \
    !defined(PETRA_NO_VECTOR_CLONES)
#define PETRA_VECTOR_CLONES [[gnu::target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")]]
// (The scanline DP, latency-bound, picks its copy by vendor as well:
// algo/stereo/scanline_dp.cpp.)
#define PETRA_HAVE_VECTOR_CLONES 1
#else
#define PETRA_VECTOR_CLONES
#define PETRA_HAVE_VECTOR_CLONES 0
#endif

namespace petra {

// True where a minimum over unsigned 16-bit lanes is native in the kernel
// copy that runs (x86-64-v3: pminuw and phminposuw; aarch64: umin, uminv);
// false for x86-64's baseline SSE2, which only has the signed one. Kernels
// whose values are never negative pick the faster form with it.
// Disparity lanes per pixel are rounded up to a multiple of this: 32 where
// the AVX-512 copy runs (a 512-bit vector holds 32 16-bit lanes, so 42
// disparities take two vectors as 64 lanes instead of one and a half as 48),
// 16 elsewhere. The extra lanes are padding that never wins: outputs are the
// same whatever the multiple.
inline constexpr int kWidestLaneMultiple = 32;  // lane_multiple() on any CPU is at most this
inline int lane_multiple() {
#if PETRA_HAVE_VECTOR_CLONES
  static const int m = __builtin_cpu_supports("x86-64-v4") ? 32 : 16;  // as the clones choose
  return m;
#else
  return 16;
#endif
}

inline bool unsigned_min_is_native() {
#if PETRA_HAVE_VECTOR_CLONES
  static const bool wide = __builtin_cpu_supports("x86-64-v3");  // as the clones choose
  return wide;
#elif defined(__x86_64__)
#if defined(__SSE4_1__)
  return true;
#else
  return false;
#endif
#else
  return true;
#endif
}

// True on an Intel CPU that runs the AVX-512 copy. Kernels whose best form
// differs between vendors there (full-width 512-bit units on Intel, split in
// two on AMD) choose by it: the scanline DP's vector width, the right-view
// winners' chain count.
inline bool intel_avx512() {
#if PETRA_HAVE_VECTOR_CLONES
  static const bool yes = [] {
    __builtin_cpu_init();
    return __builtin_cpu_supports("x86-64-v4") && __builtin_cpu_is("intel");
  }();
  return yes;
#else
  return false;
#endif
}

// The lane kernels' minimum: by value, not by reference (std::min on
// references hides a load behind a branch and stops the vectoriser).
inline std::int16_t lane_min16(std::int16_t a, std::int16_t b) {
  return a < b ? a : b;
}

}  // namespace petra
