#include "sim/calib/board_renderer.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace petra::calib {

namespace {

void gaussian_blur(std::vector<double>& img, int w, int h, double sigma) {
  const int r = static_cast<int>(std::ceil(3 * sigma));
  std::vector<double> k(static_cast<std::size_t>(2 * r + 1));
  double sum = 0;
  for (int i = -r; i <= r; ++i)
    sum += k[static_cast<std::size_t>(i + r)] = std::exp(-0.5 * i * i / (sigma * sigma));
  for (double& v : k) v /= sum;
  std::vector<double> tmp(img.size());
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      double s = 0;
      for (int i = -r; i <= r; ++i)
        s += k[static_cast<std::size_t>(i + r)] *
             img[static_cast<std::size_t>(y) * w + std::clamp(x + i, 0, w - 1)];
      tmp[static_cast<std::size_t>(y) * w + x] = s;
    }
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      double s = 0;
      for (int i = -r; i <= r; ++i)
        s += k[static_cast<std::size_t>(i + r)] *
             tmp[static_cast<std::size_t>(std::clamp(y + i, 0, h - 1)) * w + x];
      img[static_cast<std::size_t>(y) * w + x] = s;
    }
}

}  // namespace

io::GrayImage render_plane(const TsaiCamera& cam, const Albedo& albedo, const RenderOptions& opt) {
  const int w = cam.width, h = cam.height, n = std::max(1, opt.supersample);
  // Normalised image point (x, y, 1) ~ [r1 r2 T] (X, Y, 1) for plane points.
  Eigen::Matrix3d hm;
  hm.col(0) = cam.R.col(0);
  hm.col(1) = cam.R.col(1);
  hm.col(2) = cam.T_mm;
  const Eigen::Matrix3d hinv = hm.inverse();
  std::vector<double> img(static_cast<std::size_t>(w) * h);
  // Sub-samples on a sheared lattice (n-rooks: every sample has its own
  // column and row): a regular n x n grid would quantise the position of an
  // axis-aligned edge to 1/n px and bias every corner on it; here the step is
  // 1/n^2. Random jitter would be unbiased but adds visible noise.
  const int m = n * n;
  const int shear = m >= 16 ? 5 : (m >= 4 ? 3 : 1);  // coprime with m = n^2 for these n
  std::vector<double> off_u(static_cast<std::size_t>(m)), off_v(static_cast<std::size_t>(m));
  for (int k = 0; k < m; ++k) {
    off_u[static_cast<std::size_t>(k)] = (k + 0.5) / m - 0.5;
    off_v[static_cast<std::size_t>(k)] = ((k * shear) % m + 0.5) / m - 0.5;
  }
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      double sum = 0;
      for (int s = 0; s < m; ++s) {
        // pixel_to_normalised, written out: this loop runs millions of times.
        const double xd = (x + off_u[static_cast<std::size_t>(s)] - cam.cx_px) * cam.dx_mm / cam.sx;
        const double yd = (y + off_v[static_cast<std::size_t>(s)] - cam.cy_px) * cam.dy_mm;
        const double k = (1.0 + cam.kappa1 * (xd * xd + yd * yd)) / cam.f_mm;
        const Eigen::Vector3d q = hinv * Eigen::Vector3d(xd * k, yd * k, 1.0);
        double v = -1;
        if (q.z() > 0) v = albedo(q.x() / q.z(), q.y() / q.z());  // in front of the camera
        sum += v < 0 ? opt.background : v;
      }
      img[static_cast<std::size_t>(y) * w + x] = sum / m;
    }
  if (opt.blur_sigma_px > 0) gaussian_blur(img, w, h, opt.blur_sigma_px);
  std::mt19937_64 rng(opt.seed);
  std::normal_distribution<double> noise(0.0, opt.noise_sigma > 0 ? opt.noise_sigma : 1.0);
  io::GrayImage out(w, h);
  for (std::size_t k = 0; k < img.size(); ++k) {
    const double v = img[k] + (opt.noise_sigma > 0 ? noise(rng) : 0.0);
    out.pixels[k] = static_cast<std::uint8_t>(std::clamp(std::lround(v), 0L, 255L));
  }
  return out;
}

Albedo chessboard_albedo(const BoardSpec& b) {
  return [b](double x, double y) {
    const double s = b.square_mm;
    // Squares (a, c) for a in [-1, cols-1], c in [-1, rows-1] cover [a s, (a+1) s).
    const double x0 = -s - b.margin_mm, x1 = b.cols * s + b.margin_mm;
    const double y0 = -s - b.margin_mm, y1 = b.rows * s + b.margin_mm;
    if (x < x0 || x >= x1 || y < y0 || y >= y1) return -1.0;
    const double a = std::floor(x / s), c = std::floor(y / s);
    if (a < -1 || a > b.cols - 1 || c < -1 || c > b.rows - 1) return 220.0;  // margin
    const long parity = (static_cast<long>(a) + static_cast<long>(c)) & 1L;
    return parity == 0 ? 30.0 : 220.0;
  };
}

Eigen::Vector3d board_corner(const BoardSpec& b, int i, int j) {
  return {i * b.square_mm, j * b.square_mm, 0.0};
}

}  // namespace petra::calib
