#include "algo/mesh/surface_normals.hpp"

#include <Eigen/LU>
#include <cmath>

#include "algo/core/arena.hpp"

namespace petra {

namespace {

// The nine sums of the least-squares plane d = a x + b y + c (x, y relative
// to the map's origin, so the sums stay small).
struct Sums {
  double n = 0, x = 0, y = 0, xx = 0, xy = 0, yy = 0, d = 0, xd = 0, yd = 0;
  void add(const Sums& o, double sign) {
    n += sign * o.n;
    x += sign * o.x;
    y += sign * o.y;
    xx += sign * o.xx;
    xy += sign * o.xy;
    yy += sign * o.yy;
    d += sign * o.d;
    xd += sign * o.xd;
    yd += sign * o.yd;
  }
};

}  // namespace

Status validate(const NormalParams& p) {
  if (p.window < 3 || p.window > 31 || p.window % 2 == 0)
    return Error::make(Errc::invalid_argument, "normals: window %d must be odd, 3..31", p.window);
  if (!(p.min_valid > 0.0 && p.min_valid <= 1.0))
    return Error::make(Errc::invalid_argument, "normals: min_valid %.3g not in (0, 1]",
                       p.min_valid);
  return {};
}

std::size_t surface_normals_scratch_bytes(int width) {
  return arena_bytes_for<Sums>(static_cast<std::size_t>(width > 0 ? width : 0));
}

Status surface_normals(ConstDisparityMap map, const RectifiedCamera& cam,
                       const NormalParams& params, std::span<Eigen::Vector3d> normals,
                       Arena& scratch, int stride) {
  PETRA_TRY(validate(params));
  if (stride < 1) return Error::make(Errc::invalid_argument, "normals: stride %d < 1", stride);
  const int w = map.q4.width(), h = map.q4.height();
  const int packed_w = (w + stride - 1) / stride, packed_h = (h + stride - 1) / stride;
  if (normals.size() < static_cast<std::size_t>(packed_w) * static_cast<std::size_t>(packed_h))
    return Error::make(Errc::invalid_argument, "normals: output holds %zu, map has %dx%d",
                       normals.size(), w, h);
  if (!(cam.f_px > 0)) return Error::make(Errc::non_positive, "normals: f_px must be > 0");
  ArenaScope scope(scratch);
  auto cols = scratch.allocate<Sums>(static_cast<std::size_t>(w), "normal column sums");
  if (!cols) return cols.error();
  Sums* col = cols->data();
  const int r = params.window / 2;
  const double need = params.min_valid * params.window * params.window;
  const Eigen::Matrix3d to_world = cam.R.transpose();
  auto add_row = [&](int y, double sign) {
    const std::int16_t* row = map.q4.row(y);
    for (int x = 0; x < w; ++x) {
      if (!is_valid_disparity(row[x])) continue;
      const double d = disparity_px(row[x]);
      Sums s;
      s.n = 1;
      s.x = x;
      s.y = y;
      s.xx = double(x) * x;
      s.xy = double(x) * y;
      s.yy = double(y) * y;
      s.d = d;
      s.xd = x * d;
      s.yd = y * d;
      col[x].add(s, sign);
    }
  };
  for (int y = 0; y < r && y < h; ++y) add_row(y, 1);
  for (int y = 0; y < h; ++y) {
    if (y + r < h) add_row(y + r, 1);
    if (y - r - 1 >= 0) add_row(y - r - 1, -1);
    if (y % stride != 0) continue;  // the column sums move on; no normal wanted on this row
    Sums box;
    for (int x = 0; x < r && x < w; ++x) box.add(col[x], 1);
    for (int x = 0; x < w; ++x) {
      if (x + r < w) box.add(col[x + r], 1);
      if (x - r - 1 >= 0) box.add(col[x - r - 1], -1);
      if (x % stride != 0) continue;
      Eigen::Vector3d& out =
          normals[static_cast<std::size_t>(y / stride) * static_cast<std::size_t>(packed_w) +
                  static_cast<std::size_t>(x / stride)];
      out.setZero();
      if (!is_valid_disparity(map.q4(x, y)) || box.n < need) continue;
      // Normal equations of d = a x + b y + c about the box's mean position.
      const double mx = box.x / box.n, my = box.y / box.n, md = box.d / box.n;
      const double sxx = box.xx - box.n * mx * mx, sxy = box.xy - box.n * mx * my;
      const double syy = box.yy - box.n * my * my;
      const double sxd = box.xd - box.n * mx * md, syd = box.yd - box.n * my * md;
      const double det = sxx * syy - sxy * sxy;
      if (!(det > 1e-9 * (sxx * syy + 1e-12))) continue;
      const double a = (sxd * syy - syd * sxy) / det;
      const double b = (syd * sxx - sxd * sxy) / det;
      const double c = md - a * mx - b * my;
      // Back to rectified image coordinates: u = roi.x + x, v = roi.y + y.
      const double u0 = map.roi.x, v0 = map.roi.y;
      const double c_img = c - a * u0 - b * v0;
      Eigen::Vector3d n(a, b, (c_img + a * cam.cx_px + b * cam.cy_px) / cam.f_px);
      const double len = n.norm();
      if (!(len > 0)) continue;
      n /= len;
      if (n.z() > 0) n = -n;  // towards the camera (which looks along +z)
      out = to_world * n;
    }
  }
  return {};
}

}  // namespace petra
