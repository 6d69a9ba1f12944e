#include "sim/calib/corner_subpix.hpp"

#include <cmath>
#include <vector>

#include "sim/calib/image_sampling.hpp"

namespace petra::calib {

Result<Eigen::Vector2d> refine_corner(ImageView<const float> image, const Eigen::Vector2d& start,
                                      const SubpixOptions& options) {
  const int h = options.half_window;
  if (h < 1) return Error::make(Errc::invalid_argument, "subpix: half window %d < 1", h);
  const int side = 2 * h + 3;  // one extra ring for central differences
  std::vector<double> patch(static_cast<std::size_t>(side) * side);
  std::vector<double> weight(static_cast<std::size_t>(2 * h + 1) * (2 * h + 1));
  for (int j = -h; j <= h; ++j)
    for (int i = -h; i <= h; ++i) {
      const double x = static_cast<double>(i) / h, y = static_cast<double>(j) / h;
      weight[static_cast<std::size_t>(j + h) * (2 * h + 1) + (i + h)] = std::exp(-x * x - y * y);
    }
  Eigen::Vector2d c = start;
  for (int it = 0; it < options.max_iterations; ++it) {
    if (c.x() - h - 1 < 0 || c.y() - h - 1 < 0 || c.x() + h + 1 > image.width() - 1 ||
        c.y() + h + 1 > image.height() - 1)
      return Error::make(Errc::out_of_range, "subpix: window at (%.1f, %.1f) leaves the image",
                         c.x(), c.y());
    for (int j = 0; j < side; ++j)
      for (int i = 0; i < side; ++i)
        patch[static_cast<std::size_t>(j) * side + i] =
            sample_bilinear(image, c.x() + i - h - 1, c.y() + j - h - 1);
    double a = 0, b = 0, d = 0, bx = 0, by = 0;
    for (int j = -h; j <= h; ++j)
      for (int i = -h; i <= h; ++i) {
        const std::size_t row = static_cast<std::size_t>(j + h + 1) * side;
        const std::size_t col = static_cast<std::size_t>(i + h + 1);
        const double gx = patch[row + col + 1] - patch[row + col - 1];
        const double gy = patch[row + side + col] - patch[row - side + col];
        const double w = weight[static_cast<std::size_t>(j + h) * (2 * h + 1) + (i + h)];
        const double gxx = w * gx * gx, gxy = w * gx * gy, gyy = w * gy * gy;
        a += gxx;
        b += gxy;
        d += gyy;
        bx += gxx * i + gxy * j;
        by += gxy * i + gyy * j;
      }
    const double det = a * d - b * b;
    // Two independent gradient directions are needed; an edge or flat patch
    // has det close to zero relative to the squared trace.
    if (!(det > 1e-6 * (a + d) * (a + d)))
      return Error::make(Errc::degenerate, "subpix: no corner structure at (%.1f, %.1f)", c.x(),
                         c.y());
    const Eigen::Vector2d step((d * bx - b * by) / det, (a * by - b * bx) / det);
    c += step;
    if ((c - start).norm() > h)
      return Error::make(Errc::no_solution, "subpix: estimate left the window around (%.1f, %.1f)",
                         start.x(), start.y());
    if (step.norm() < options.epsilon_px) break;
  }
  return c;
}

}  // namespace petra::calib
