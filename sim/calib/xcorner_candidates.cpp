#include "sim/calib/xcorner_candidates.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "sim/calib/corner_subpix.hpp"
#include "sim/calib/image_sampling.hpp"
#include "sim/io/image_io.hpp"

namespace petra::calib {

namespace {

constexpr int kRingSamples = 64;
constexpr double kPi = 3.14159265358979323846;

struct Offset {
  int dx, dy;
};

std::array<Offset, 16> chess_ring(int r) {
  std::array<Offset, 16> ring{};
  for (int k = 0; k < 16; ++k) {
    const double a = 2 * kPi * k / 16;
    ring[static_cast<std::size_t>(k)] = {static_cast<int>(std::lround(r * std::cos(a))),
                                         static_cast<int>(std::lround(r * std::sin(a)))};
  }
  return ring;
}

io::FloatImage chess_response(ImageView<const float> img, int r) {
  const std::array<Offset, 16> ring = chess_ring(r);
  io::FloatImage out(img.width(), img.height(), 0.0f);
  const int m = r + 1;
  for (int y = m; y < img.height() - m; ++y)
    for (int x = m; x < img.width() - m; ++x) {
      float s[16];
      float ring_sum = 0;
      for (int k = 0; k < 16; ++k) {
        s[k] =
            img(x + ring[static_cast<std::size_t>(k)].dx, y + ring[static_cast<std::size_t>(k)].dy);
        ring_sum += s[k];
      }
      float sum_response = 0, diff_response = 0;
      for (int n = 0; n < 4; ++n) sum_response += std::abs(s[n] + s[n + 8] - s[n + 4] - s[n + 12]);
      for (int n = 0; n < 8; ++n) diff_response += std::abs(s[n] - s[n + 8]);
      const float centre =
          (img(x, y) + img(x - 1, y) + img(x + 1, y) + img(x, y - 1) + img(x, y + 1)) / 5.0f;
      const float mean_response = 16.0f * std::abs(ring_sum / 16.0f - centre);
      out.view()(x, y) = sum_response - diff_response - mean_response;
    }
  return out;
}

struct Peak {
  int x, y;
  float response;
};

std::vector<Peak> local_maxima(ImageView<const float> resp, int radius) {
  std::vector<Peak> peaks;
  for (int y = radius; y < resp.height() - radius; ++y)
    for (int x = radius; x < resp.width() - radius; ++x) {
      const float v = resp(x, y);
      if (!(v > 0)) continue;
      bool is_max = true;
      for (int dy = -radius; dy <= radius && is_max; ++dy)
        for (int dx = -radius; dx <= radius; ++dx) {
          const float w = resp(x + dx, y + dy);
          // Ties go to the first pixel in raster order, so a plateau gives one peak.
          if (w > v || (w == v && (dy < 0 || (dy == 0 && dx < 0)))) {
            is_max = false;
            break;
          }
        }
      if (is_max) peaks.push_back({x, y, v});
    }
  return peaks;
}

// Mean of two line directions given as angles (period pi).
double mean_line_angle(double a, double b) {
  const double s = std::sin(2 * a) + std::sin(2 * b);
  const double c = std::cos(2 * a) + std::cos(2 * b);
  double m = 0.5 * std::atan2(s, c);
  if (m < 0) m += kPi;
  return m;
}

double wrap_pi(double a) {  // to (-pi, pi]
  while (a > kPi) a -= 2 * kPi;
  while (a <= -kPi) a += 2 * kPi;
  return a;
}

}  // namespace

RingShape analyse_ring(ImageView<const float> smooth, const Eigen::Vector2d& uv, double radius,
                       double min_contrast) {
  RingShape shape;
  if (uv.x() - radius < 1 || uv.y() - radius < 1 || uv.x() + radius > smooth.width() - 2 ||
      uv.y() + radius > smooth.height() - 2)
    return shape;
  std::array<double, kRingSamples> raw{}, p{};
  for (int k = 0; k < kRingSamples; ++k) {
    const double a = 2 * kPi * k / kRingSamples;
    raw[static_cast<std::size_t>(k)] =
        sample_bilinear(smooth, uv.x() + radius * std::cos(a), uv.y() + radius * std::sin(a));
  }
  for (int k = 0; k < kRingSamples; ++k)
    p[static_cast<std::size_t>(k)] =
        0.25 * raw[static_cast<std::size_t>((k + kRingSamples - 1) % kRingSamples)] +
        0.5 * raw[static_cast<std::size_t>(k)] +
        0.25 * raw[static_cast<std::size_t>((k + 1) % kRingSamples)];
  const auto [lo_it, hi_it] = std::minmax_element(p.begin(), p.end());
  const double lo = *lo_it, hi = *hi_it;
  if (hi - lo < min_contrast) return shape;
  const double mid = 0.5 * (lo + hi);
  double crossing[kRingSamples];
  int n = 0;
  double bright = 0, dark = 0;
  int n_bright = 0, n_dark = 0;
  for (int k = 0; k < kRingSamples; ++k) {
    const double a = p[static_cast<std::size_t>(k)] - mid;
    const double b = p[static_cast<std::size_t>((k + 1) % kRingSamples)] - mid;
    if (a >= 0) {
      bright += p[static_cast<std::size_t>(k)];
      ++n_bright;
    } else {
      dark += p[static_cast<std::size_t>(k)];
      ++n_dark;
    }
    if ((a >= 0) != (b >= 0)) crossing[n++] = 2 * kPi * (k + a / (a - b)) / kRingSamples;
  }
  shape.crossings = n;
  if (n != 4 || n_bright == 0 || n_dark == 0) return shape;
  shape.contrast = bright / n_bright - dark / n_dark;
  if (shape.contrast < min_contrast) return shape;
  // Two straight edges through the point: opposite crossings pi apart, and
  // no sector so narrow that it is more likely noise than a square.
  constexpr double kOppositeTolerance = 25.0 * kPi / 180.0;
  constexpr double kMinSector = 20.0 * kPi / 180.0;
  if (std::abs(wrap_pi(crossing[2] - crossing[0] - kPi)) > kOppositeTolerance ||
      std::abs(wrap_pi(crossing[3] - crossing[1] - kPi)) > kOppositeTolerance)
    return shape;
  for (int k = 0; k < 4; ++k) {
    double sector = crossing[(k + 1) % 4] - crossing[k];
    if (sector < 0) sector += 2 * kPi;
    if (sector < kMinSector) return shape;
  }
  shape.line_angle[0] = mean_line_angle(crossing[0], crossing[2]);
  shape.line_angle[1] = mean_line_angle(crossing[1], crossing[3]);
  shape.is_xcorner = true;
  return shape;
}

std::vector<XCorner> find_xcorners(ImageView<const float> smooth, ImageView<const float> raw,
                                   const XCornerOptions& options) {
  const int r = options.ring_radius_px;
  const io::FloatImage resp = chess_response(smooth, r);
  std::vector<Peak> peaks = local_maxima(resp.view(), 2);
  std::sort(peaks.begin(), peaks.end(),
            [](const Peak& a, const Peak& b) { return a.response > b.response; });
  if (peaks.empty()) return {};
  // The board supplies about expected_corners peaks of similar strength; a
  // fraction of a typical one separates them from texture without an
  // absolute level that would depend on exposure.
  const std::size_t ref_index = std::min(
      peaks.size() - 1, static_cast<std::size_t>(std::max(1, options.expected_corners / 2)));
  const float threshold = 0.1f * peaks[ref_index].response;
  std::vector<XCorner> out;
  SubpixOptions sp;
  sp.half_window = options.subpix_half_window;
  for (const Peak& pk : peaks) {
    if (pk.response < threshold || static_cast<int>(out.size()) >= options.max_candidates) break;
    auto refined = refine_corner(raw, Eigen::Vector2d(pk.x, pk.y), sp);
    if (!refined) continue;
    if ((*refined - Eigen::Vector2d(pk.x, pk.y)).norm() > 0.5 * r) continue;
    bool duplicate = false;
    for (const XCorner& c : out)
      if ((c.uv - *refined).squaredNorm() < 4.0) {
        duplicate = true;
        break;
      }
    if (duplicate) continue;
    const RingShape shape = analyse_ring(smooth, *refined, r, options.min_contrast);
    if (!shape.is_xcorner) continue;
    XCorner c;
    c.uv = *refined;
    c.line_angle[0] = shape.line_angle[0];
    c.line_angle[1] = shape.line_angle[1];
    c.contrast = shape.contrast;
    c.response = pk.response;
    out.push_back(c);
  }
  return out;
}

}  // namespace petra::calib
