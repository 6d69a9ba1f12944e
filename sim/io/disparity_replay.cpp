#include "sim/io/disparity_replay.hpp"

#include <cmath>

#include "algo/core/disparity.hpp"
#include "sim/io/image_io.hpp"

namespace petra::io {

Result<std::vector<std::int16_t>> read_disparity_q4(const std::string& path, int width,
                                                    int height) {
  auto pfm = read_pfm(path);
  if (!pfm) return pfm.error();
  if (pfm->width != width || pfm->height != height)
    return Error::make(Errc::invalid_argument, "--disparity %s: %dx%d, not the images' %dx%d",
                       path.c_str(), pfm->width, pfm->height, width, height);
  std::vector<std::int16_t> q4(static_cast<std::size_t>(width) * static_cast<std::size_t>(height),
                               kInvalidDisparity);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const float d = pfm->view()(x, y);
      if (std::isfinite(d) && std::abs(d) < 2000)
        q4[static_cast<std::size_t>(y) * width + x] = disparity_q4(d);
    }
  return q4;
}

}  // namespace petra::io
