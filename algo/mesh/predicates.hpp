// Exact geometric predicates on integer points (|x|, |y| <= 2^20). Integer
// coordinates make them exact without adaptive arithmetic: orient2d fits in
// 64 bits, incircle in 128 bits (g++ __int128, present on x86-64 and aarch64).
#pragma once

#include <cstdint>

namespace petra {

inline constexpr std::int32_t kPredicateMaxAbsCoord = 1 << 20;

struct IntPoint {
  std::int32_t x = 0;
  std::int32_t y = 0;
  friend constexpr bool operator==(const IntPoint&, const IntPoint&) = default;
};

// > 0 when a, b, c turn counter-clockwise (x right, y up; in image
// coordinates, with y down, the picture is mirrored), 0 when collinear.
constexpr std::int64_t orient2d(IntPoint a, IntPoint b, IntPoint c) {
  return static_cast<std::int64_t>(b.x - a.x) * (c.y - a.y) -
         static_cast<std::int64_t>(b.y - a.y) * (c.x - a.x);
}

// Sign of the in-circle determinant: > 0 when d lies strictly inside the
// circle through a, b, c (given with orient2d(a, b, c) > 0), 0 on it.
inline int incircle_sign(IntPoint a, IntPoint b, IntPoint c, IntPoint d) {
  __extension__ using int128 = __int128;
  const std::int64_t adx = a.x - d.x, ady = a.y - d.y;
  const std::int64_t bdx = b.x - d.x, bdy = b.y - d.y;
  const std::int64_t cdx = c.x - d.x, cdy = c.y - d.y;
  const std::int64_t alift = adx * adx + ady * ady;
  const std::int64_t blift = bdx * bdx + bdy * bdy;
  const std::int64_t clift = cdx * cdx + cdy * cdy;
  const int128 det = int128{alift} * (bdx * cdy - cdx * bdy) +
                     int128{blift} * (cdx * ady - adx * cdy) +
                     int128{clift} * (adx * bdy - bdx * ady);
  return det > 0 ? 1 : (det < 0 ? -1 : 0);
}

// The same sign in 64-bit arithmetic, exact when every coordinate difference
// is below 2^14 (lifts < 2^29, products < 2^58, the sum of three < 2^60).
inline constexpr std::int32_t kSmallPredicateSpan = 1 << 14;
inline int incircle_sign_small(IntPoint a, IntPoint b, IntPoint c, IntPoint d) {
  const std::int64_t adx = a.x - d.x, ady = a.y - d.y;
  const std::int64_t bdx = b.x - d.x, bdy = b.y - d.y;
  const std::int64_t cdx = c.x - d.x, cdy = c.y - d.y;
  const std::int64_t det = (adx * adx + ady * ady) * (bdx * cdy - cdx * bdy) +
                           (bdx * bdx + bdy * bdy) * (cdx * ady - adx * cdy) +
                           (cdx * cdx + cdy * cdy) * (adx * bdy - bdx * ady);
  return det > 0 ? 1 : (det < 0 ? -1 : 0);
}

}  // namespace petra
