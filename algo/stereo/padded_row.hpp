// One image row copied with border replication, so row filters (Canny's
// smoothing, the matcher's census and costs) run without bounds checks.
#pragma once

#include <algorithm>
#include <cstdint>

#include "algo/core/image_view.hpp"

namespace petra {

// Copies row `y` (clamped to the image) over columns [x0, x0 + n) into `out`
// (n bytes), replicating the first and last column where the span leaves the image.
inline void padded_row(ConstGray8View img, int y, int x0, int n, std::uint8_t* out) {
  const std::uint8_t* s = img.row(std::clamp(y, 0, img.height() - 1));
  const int last = img.width() - 1;
  if (x0 >= 0 && x0 + n - 1 <= last) {  // the interior: a plain copy
    std::copy(s + x0, s + x0 + n, out);
    return;
  }
  for (int i = 0; i < n; ++i) out[i] = s[std::clamp(x0 + i, 0, last)];
}

}  // namespace petra
