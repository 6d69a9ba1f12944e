// Steps 4-5 of algo/stereo/match_dp for one ROI row: from each pixel's winning lane
// (and the path costs around it), the checks that reject wrong matches, the
// sub-pixel parabola and the confidence. Part of algo/stereo/match_dp; exposed for
// tests. Integer results throughout; the two divisions per pixel are done in
// float where the operands are exact and the truncated quotient provably
// equals the integer one (|numerator| < 2^24), so the loop vectorises.
// Memory: the caller's rows (SelectRowScratch: 5 int32 per pixel); no heap.
#pragma once

#include <cstdint>

namespace petra::match {

// Why a pixel has no disparity (the first check it fails), or kMatched.
enum Reason : std::uint8_t {
  kMatched,
  kShadowLeft,
  kRange,
  kLeftRight,
  kUniqueness,
  kCost,
  kShadowRight,
};

struct SelectRowInputs {
  int w = 0;                             // ROI width
  const std::int16_t* k1 = nullptr;      // winning lane per pixel (w)
  const std::int16_t* best = nullptr;    // its path cost S (w)
  const std::int16_t* second = nullptr;  // best S more than one lane away (w)
  const std::int16_t* S = nullptr;       // path costs: pixel i's lane k at S[i * s_stride + k]
  int s_stride = 0;                      // (lanes -1 and D are readable: guard lanes)
  const std::uint16_t* cost =
      nullptr;  // aggregated cost: pixel i's lane k at cost[i * c_stride + k]
  int c_stride = 0;
  const std::int16_t* lo = nullptr;  // allowed lanes [lo, hi] per pixel (w)
  const std::int16_t* hi = nullptr;
  const std::int16_t* right_lane = nullptr;   // right-view winner lane by reversed index w-1-i+k
  const std::uint8_t* left_shadow = nullptr;  // w flags (nonzero: shadow)
  // Right shadow flags of image columns x0 - disp_max .. x0 + w - 1 - disp_min
  // (w + D - 1 entries): pixel i at lane k reads right_shadow[i + D - 1 - k].
  const std::uint8_t* right_shadow = nullptr;
  int lanes = 0;  // D, real lanes
  int x0 = 0;     // image column of pixel 0
  int disp_min = 0;
  int image_width = 0;
  int lr_tolerance_px = 0;
  int uniqueness_pct = 0;
  long cost_ceiling = 0;  // aggregated cost above this: rejected
};

// Per-pixel scratch of select_row, 5 w int32 in all.
struct SelectRowScratch {
  std::int32_t* below = nullptr;  // S at k1 - 1
  std::int32_t* above = nullptr;  // S at k1 + 1
  std::int32_t* right = nullptr;  // right-view winner lane at k1
  std::int32_t* cost = nullptr;   // aggregated cost at k1
  std::int32_t* shade = nullptr;  // right shadow flag at k1
};

struct RejectCounts {
  int range = 0, lr = 0, uniqueness = 0, cost = 0, shadow_right = 0;
};

// Disparity (Q4, kInvalidDisparity when rejected) into out[0..w), the first
// failed check into why[0..w), the confidence into conf[0..w) unless null
// (0 = invalid, else 1..255); returns the rejection counts of the row.
RejectCounts select_row(const SelectRowInputs& in, const SelectRowScratch& scratch,
                        std::int16_t* out, std::uint8_t* conf, std::uint8_t* why);

}  // namespace petra::match
