// PETRA_VECTOR_CLONES marks a lane kernel (a loop over disparity lanes the
// compiler vectorises) to be compiled twice on x86-64: for the baseline
// (SSE2) and for x86-64-v3 (AVX2, 256-bit vectors), the copy being chosen
// once at program load from the CPU's features (GCC function multiversioning:
// no heap, no intrinsics, same integer arithmetic, so bit-identical outputs).
// Elsewhere (aarch64 flight build: NEON) it is empty and the kernel is
// compiled once for the target. Define PETRA_NO_VECTOR_CLONES to measure the
// baseline copy alone.
#pragma once

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && \
    !defined(PETRA_NO_VECTOR_CLONES)
#define PETRA_VECTOR_CLONES [[gnu::target_clones("arch=x86-64-v3", "default")]]
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

}  // namespace petra
