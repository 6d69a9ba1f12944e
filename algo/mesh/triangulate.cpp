#include "algo/mesh/triangulate.hpp"

namespace petra {

Result<TriangulationStats> triangulate_disparity(const RectifiedPair& rect,
                                                 ConstDisparityMap disparity,
                                                 std::span<Eigen::Vector3d> xyz_mm,
                                                 std::span<PixelPos> pixels, int factor) {
  const std::size_t capacity = xyz_mm.size() < pixels.size() ? xyz_mm.size() : pixels.size();
  const Rect& roi = disparity.roi;
  if (roi.x < 0 || roi.y < 0 || roi.x + roi.w > 32767 || roi.y + roi.h > 32767)
    return Error::make(Errc::out_of_range, "triangulate: ROI (%d,%d %dx%d) outside 0..32767", roi.x,
                       roi.y, roi.w, roi.h);
  if (factor < 1 || factor > 8)
    return Error::make(Errc::invalid_argument, "triangulate: factor %d not within 1..8", factor);
  const double f = factor, centre = 0.5 * (factor - 1);
  TriangulationStats stats;
  for (int y = 0; y < disparity.q4.height(); ++y) {
    const std::int16_t* row = disparity.q4.row(y);
    for (int x = 0; x < disparity.q4.width(); ++x) {
      const std::int16_t q = row[x];
      if (!is_valid_disparity(q)) continue;
      if (q <= 0) {
        ++stats.rejected;
        continue;
      }
      if (stats.points == capacity)
        return Error::make(Errc::capacity_exceeded,
                           "triangulate: more valid disparities than the point budget %zu",
                           capacity);
      const double u = (roi.x + x) * f + centre, v = (roi.y + y) * f + centre;
      auto p = rectified_point(rect, u, v, disparity_px(q) * f);
      if (!p) {
        ++stats.rejected;
        continue;
      }
      xyz_mm[stats.points] = *p;
      pixels[stats.points] = {static_cast<std::int16_t>(roi.x + x),
                              static_cast<std::int16_t>(roi.y + y)};
      ++stats.points;
    }
  }
  return stats;
}

}  // namespace petra
