// A StepClock source of this thread's CPU time: what the rover's one core
// would spend on a step, unaffected by other load on a shared ground machine.
#pragma once

#include <time.h>

#include <cstdint>

namespace petra::sim {

inline std::uint64_t thread_cpu_ns(void* /*context*/) {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<std::uint64_t>(ts.tv_sec) * 1000000000ull +
         static_cast<std::uint64_t>(ts.tv_nsec);
}

}  // namespace petra::sim
