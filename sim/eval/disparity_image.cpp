#include "sim/eval/disparity_image.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace petra::eval {

io::FloatImage to_float_image(const ConstDisparityMap& map, int width, int height) {
  io::FloatImage img(width, height, std::numeric_limits<float>::infinity());
  for (int y = 0; y < map.q4.height(); ++y) {
    const int yy = map.roi.y + y;
    if (yy < 0 || yy >= height) continue;
    for (int x = 0; x < map.q4.width(); ++x) {
      const int xx = map.roi.x + x;
      const std::int16_t q = map.q4(x, y);
      if (xx < 0 || xx >= width || !is_valid_disparity(q)) continue;
      img.data[static_cast<std::size_t>(yy) * width + xx] = static_cast<float>(disparity_px(q));
    }
  }
  return img;
}

void fill_invalid_background(ImageView<float> d, Rect area) {
  const float inf = std::numeric_limits<float>::infinity();
  std::vector<float> left(static_cast<std::size_t>(std::max(area.w, 0)));
  for (int y = area.y; y < area.y + area.h; ++y) {
    float* row = d.row(y) + area.x;
    float last = inf;
    for (int x = 0; x < area.w; ++x) {
      if (std::isfinite(row[x])) last = row[x];
      left[static_cast<std::size_t>(x)] = last;
    }
    float next = inf;
    for (int x = area.w - 1; x >= 0; --x) {
      if (std::isfinite(row[x])) {
        next = row[x];
        continue;
      }
      // inf marks "no valid neighbour on that side": min picks the other.
      row[x] = std::min(left[static_cast<std::size_t>(x)], next);
    }
  }
}

void fill_invalid_background(ImageView<float> d) {
  fill_invalid_background(d, Rect{0, 0, d.width(), d.height()});
}

}  // namespace petra::eval
