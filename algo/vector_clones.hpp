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
#else
#define PETRA_VECTOR_CLONES
#endif
