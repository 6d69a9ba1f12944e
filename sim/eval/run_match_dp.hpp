// Runs the onboard matcher (algo/stereo/match_dp) over a whole image pair with a
// budget sized for it, as the ground tools and the benchmark do; returns the
// full-size float disparity (invalid = +inf).
#pragma once

#include "algo/stereo/match_dp.hpp"
#include "sim/io/image_io.hpp"

namespace petra::eval {

struct MatchRun {
  io::FloatImage disparity;
  MatchDpStats stats;
};

Result<MatchRun> run_match_dp(ConstGray8View left, ConstGray8View right, Rect roi,
                              const MatchDpParams& params);

}  // namespace petra::eval
