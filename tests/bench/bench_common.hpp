// What the whole-chain benchmarks share: the thread's CPU clock (the chain's
// step clock), and leaving with a message when a setup step fails.
#pragma once

#include <time.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <utility>

#include "algo/core/result.hpp"

namespace petra::bench {

inline std::uint64_t thread_cpu_ns(void*) {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<std::uint64_t>(ts.tv_sec) * 1000000000ull +
         static_cast<std::uint64_t>(ts.tv_nsec);
}

[[noreturn]] inline void die(const char* bench, const std::string& what) {
  std::fprintf(stderr, "%s: %s\n", bench, what.c_str());
  std::exit(1);
}

template <class T>
T must(const char* bench, Result<T> r, const std::string& what) {
  if (!r) die(bench, what + ": " + r.error().message);
  return std::move(*r);
}

}  // namespace petra::bench
