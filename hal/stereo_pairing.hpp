// Pairing left and right frames by capture time: two free-running or
// triggered cameras deliver frames with their own timestamps; a pair is valid
// when the two are at most max_skew apart. Otherwise the older frame is
// dropped and its camera read again. Pure, for the V4L2 and libcamera backends.
#pragma once

#include <cstdint>

namespace petra::hal {

enum class PairStep : std::uint8_t { pair, next_left, next_right };

constexpr std::int64_t abs_skew_ns(std::int64_t left_ns, std::int64_t right_ns) {
  return left_ns > right_ns ? left_ns - right_ns : right_ns - left_ns;
}

constexpr PairStep pair_step(std::int64_t left_ns, std::int64_t right_ns,
                             std::int64_t max_skew_ns) {
  if (abs_skew_ns(left_ns, right_ns) <= max_skew_ns) return PairStep::pair;
  return left_ns < right_ns ? PairStep::next_left : PairStep::next_right;
}

}  // namespace petra::hal
