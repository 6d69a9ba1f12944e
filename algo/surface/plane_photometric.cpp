#include "algo/surface/plane_photometric.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

namespace petra {

namespace {

// Gray level of the right image at (x, v) by linear interpolation along the
// row (rows are aligned: v is whole), and its derivative in x.
struct Sample {
  double value = 0;
  double dx = 0;
};

bool sample_row(ConstGray8View right, Rect valid, double x, int v, Sample& s) {
  const int x0 = static_cast<int>(std::floor(x));
  if (x0 - 1 < valid.x || x0 + 2 >= valid.x + valid.w || v < valid.y || v >= valid.y + valid.h)
    return false;
  const std::uint8_t* row = right.row(v);
  const double t = x - x0;
  const double r0 = row[x0], r1 = row[x0 + 1];
  s.value = r0 + t * (r1 - r0);
  // Central difference of the interpolated row: smooth across pixel borders.
  const double rm = row[x0 - 1] + t * (r0 - row[x0 - 1]);
  const double rp = r1 + t * (row[x0 + 2] - r1);
  s.dx = 0.5 * (rp - rm);
  return true;
}

// Unknowns: plane (a, b, c), gain, offset, left blur along the row and the column.
using Vec7 = Eigen::Matrix<double, 7, 1>;
using Mat7 = Eigen::Matrix<double, 7, 7>;

// Second differences of the left image at a pixel, along the row and the
// column (zero at the image border).
double second_diff_row(ConstGray8View im, int u, int v) {
  if (u < 1 || u + 1 >= im.width()) return 0;
  return static_cast<double>(im(u - 1, v)) + static_cast<double>(im(u + 1, v)) -
         2.0 * static_cast<double>(im(u, v));
}
double second_diff_col(ConstGray8View im, int u, int v) {
  if (v < 1 || v + 1 >= im.height()) return 0;
  return static_cast<double>(im(u, v - 1)) + static_cast<double>(im(u, v + 1)) -
         2.0 * static_cast<double>(im(u, v));
}

// Plane and photometric gain/offset of one iterate.
struct State {
  DisparityPlane plane;
  double gain = 1;
  double offset = 0;
  // Blur of the left image relative to the right, along the row and the
  // column: the left gray level is compared as L + wx Lxx + wy Lyy (a
  // 3-tap kernel [w, 1 - 2w, w]; negative: the left is the blurrier).
  double wx = 0, wy = 0;
};

// The left gray level at p under the state's relative blur; the second
// differences are returned for the Jacobian.
double left_value(ConstGray8View left, const PixelPos& p, const State& s, double& dxx,
                  double& dyy) {
  dxx = second_diff_row(left, p.u, p.v);
  dyy = second_diff_col(left, p.u, p.v);
  return static_cast<double>(left(p.u, p.v)) + s.wx * dxx + s.wy * dyy;
}

// Gray residuals L - g R - o at the state, truncated at tau (pixels that
// leave the right image count as tau): a cost that compares planes fairly.
double truncated_cost(ConstGray8View left, ConstGray8View right, Rect valid,
                      std::span<const PixelPos> pixels, const State& s, double tau) {
  double sum = 0;
  for (const PixelPos& p : pixels) {
    Sample r;
    if (!sample_row(right, valid, p.u - s.plane.at(p.u, p.v), p.v, r)) {
      sum += tau * tau;
      continue;
    }
    double dxx, dyy;
    const double e = left_value(left, p, s, dxx, dyy) - s.gain * r.value - s.offset;
    sum += std::min(e * e, tau * tau);
  }
  return pixels.empty() ? 0.0 : sum / static_cast<double>(pixels.size());
}

// One Gauss-Newton pass: the normal equations of the residuals within
// `limit`; returns the RMS of those residuals and how many there were.
struct Pass {
  Mat7 H = Mat7::Zero();
  Vec7 g = Vec7::Zero();
  double rms = 0;
  long used = 0;
};

Pass gauss_newton_pass(ConstGray8View left, ConstGray8View right, Rect valid,
                       std::span<const PixelPos> pixels, const State& s, double limit) {
  Pass pass;
  double sq = 0;
  for (const PixelPos& p : pixels) {
    Sample r;
    if (!sample_row(right, valid, p.u - s.plane.at(p.u, p.v), p.v, r)) continue;
    double dxx, dyy;
    const double e = left_value(left, p, s, dxx, dyy) - s.gain * r.value - s.offset;
    if (std::abs(e) > limit) continue;
    // d grows -> the right sample moves left: de/dd = +g R_x.
    const double ed = s.gain * r.dx;
    Vec7 J;
    J << ed * (p.u - s.plane.u0), ed * (p.v - s.plane.v0), ed, -r.value, -1.0, dxx, dyy;
    pass.H.selfadjointView<Eigen::Lower>().rankUpdate(J);
    pass.g += J * e;
    sq += e * e;
    ++pass.used;
  }
  pass.H = pass.H.selfadjointView<Eigen::Lower>();
  pass.rms = pass.used > 0 ? std::sqrt(sq / static_cast<double>(pass.used)) : 0.0;
  return pass;
}

// The bounding box of the face's pixels: its corners measure how far a
// plane moved.
struct Corners {
  int u_min = std::numeric_limits<int>::max(), u_max = std::numeric_limits<int>::min();
  int v_min = std::numeric_limits<int>::max(), v_max = std::numeric_limits<int>::min();

  // The largest |q - r| at a corner.
  double shift(const DisparityPlane& q, const DisparityPlane& r) const {
    double m = 0;
    for (int u : {u_min, u_max})
      for (int v : {v_min, v_max}) m = std::max(m, std::abs(q.at(u, v) - r.at(u, v)));
    return m;
  }
  // The largest |d| at a corner.
  double largest(const DisparityPlane& d) const {
    double moved = 0;
    for (int u : {u_min, u_max})
      for (int v : {v_min, v_max}) moved = std::max(moved, std::abs(d.at(u, v)));
    return moved;
  }
};

Status check_inputs(ConstGray8View left, ConstGray8View right, Rect right_valid,
                    const DisparityPlane& initial) {
  if (left.empty() || left.width() != right.width() || left.height() != right.height())
    return Error::make(Errc::invalid_argument, "photometric plane: images %dx%d and %dx%d",
                       left.width(), left.height(), right.width(), right.height());
  if (!right_valid.inside(right.width(), right.height()))
    return Error::make(Errc::invalid_argument,
                       "photometric plane: right area (%d,%d %dx%d) not inside the image",
                       right_valid.x, right_valid.y, right_valid.w, right_valid.h);
  if (!(std::isfinite(initial.a) && std::isfinite(initial.b) && std::isfinite(initial.c)))
    return Error::make(Errc::invalid_argument, "photometric plane: initial plane not finite");
  return {};
}

Result<Corners> pixel_corners(ConstGray8View left, std::span<const PixelPos> pixels) {
  Corners c;
  for (const PixelPos& p : pixels) {
    if (p.u < 0 || p.v < 0 || p.u >= left.width() || p.v >= left.height())
      return Error::make(Errc::out_of_range, "photometric plane: pixel (%d, %d) outside the image",
                         p.u, p.v);
    c.u_min = std::min<int>(c.u_min, p.u);
    c.u_max = std::max<int>(c.u_max, p.u);
    c.v_min = std::min<int>(c.v_min, p.v);
    c.v_max = std::max<int>(c.v_max, p.v);
  }
  return c;
}

// What the Gauss-Newton iterations read.
struct Problem {
  ConstGray8View left, right;
  Rect right_valid;
  std::span<const PixelPos> pixels;
  const DisparityPlane& initial;
  const PhotometricPlaneParams& params;
  Corners corners;
};

// Gain and offset for the initial plane first (linear in them), so the
// first trim and the cost compare planes, not exposures. False when they
// cannot be fitted.
bool fit_exposure(const Problem& q, State& s) {
  const double inf = std::numeric_limits<double>::infinity();
  Pass p = gauss_newton_pass(q.left, q.right, q.right_valid, q.pixels, s, inf);
  if (p.used < q.params.min_pixels) return false;
  const Eigen::Matrix2d H2 = p.H.block<2, 2>(3, 3);
  const Eigen::Vector2d g2 = p.g.segment<2>(3);
  const Eigen::Vector2d step = H2.ldlt().solve(-g2);
  if (!step.allFinite()) return false;
  s.gain += step(0);
  s.offset += step(1);
  return true;
}

// Gauss-Newton on the plane, exposure and blur from s, residuals trimmed
// from tau on. False when it stopped without a usable iterate (too few
// pixels, a singular step, or the plane left the basin).
bool iterate(const Problem& q, double tau, State& s, PhotometricPlaneFit& fit) {
  const PhotometricPlaneParams& params = q.params;
  double limit = tau;
  for (int it = 0; it < params.max_iterations; ++it) {
    const Pass p = gauss_newton_pass(q.left, q.right, q.right_valid, q.pixels, s, limit);
    fit.iterations = it + 1;
    if (p.used < params.min_pixels) return false;
    const Vec7 step = p.H.ldlt().solve(-p.g);
    if (!step.allFinite()) return false;
    s.plane.a += step(0);
    s.plane.b += step(1);
    s.plane.c += step(2);
    s.gain += step(3);
    s.offset += step(4);
    s.wx += step(5);
    s.wy += step(6);
    if (q.corners.shift(s.plane, q.initial) > 2.0 * params.max_shift_px)
      return false;  // left the basin
    fit.pixels = p.used;
    limit = params.trim_sigma * std::max(p.rms, 0.5);
    // Converged when no corner of the face moves by a thousandth of a pixel.
    DisparityPlane d{step(0), step(1), step(2), s.plane.u0, s.plane.v0};
    if (q.corners.largest(d) < 1e-3) break;
  }
  return true;
}

}  // namespace

Status validate(const PhotometricPlaneParams& p) {
  if (p.max_iterations < 1 || p.max_iterations > 50)
    return Error::make(Errc::out_of_range, "photometric plane: max_iterations %d not in 1..50",
                       p.max_iterations);
  if (!(p.trim_sigma > 1.0 && p.trim_sigma < 100.0))
    return Error::make(Errc::out_of_range, "photometric plane: trim_sigma %.3g not in (1, 100)",
                       p.trim_sigma);
  if (!(p.max_shift_px > 0.0 && p.max_shift_px <= 8.0))
    return Error::make(Errc::out_of_range, "photometric plane: max_shift_px %.3g not in (0, 8]",
                       p.max_shift_px);
  if (p.edge_px < 0 || p.edge_px > 5)
    return Error::make(Errc::out_of_range, "photometric plane: edge_px %d not in 0..5", p.edge_px);
  if (p.min_pixels < 10 || p.min_pixels > 1000000)
    return Error::make(Errc::out_of_range, "photometric plane: min_pixels %d not in 10..1e6",
                       p.min_pixels);
  if (p.max_pixels < p.min_pixels || p.max_pixels > 1000000)
    return Error::make(Errc::out_of_range, "photometric plane: max_pixels %d not in %d..1e6",
                       p.max_pixels, p.min_pixels);
  return {};
}

Result<PhotometricPlaneFit> refine_plane_photometric(ConstGray8View left, ConstGray8View right,
                                                     Rect right_valid,
                                                     std::span<const PixelPos> pixels,
                                                     const DisparityPlane& initial,
                                                     const PhotometricPlaneParams& params) {
  PETRA_TRY(validate(params));
  PETRA_TRY(check_inputs(left, right, right_valid, initial));
  auto corners = pixel_corners(left, pixels);
  if (!corners) return corners.error();
  PhotometricPlaneFit fit;
  fit.plane = initial;
  if (static_cast<long>(pixels.size()) < params.min_pixels) return fit;

  const Problem q{left, right, right_valid, pixels, initial, params, *corners};
  State s;
  s.plane = initial;
  if (!fit_exposure(q, s)) return fit;
  const double inf = std::numeric_limits<double>::infinity();
  const Pass first = gauss_newton_pass(left, right, right_valid, pixels, s, inf);
  const double tau = params.trim_sigma * std::max(first.rms, 0.5);
  const double cost_before = truncated_cost(left, right, right_valid, pixels, s, tau);
  fit.rms_before = std::sqrt(cost_before);
  if (!iterate(q, tau, s, fit)) return fit;
  const double cost_after = truncated_cost(left, right, right_valid, pixels, s, tau);
  fit.rms_after = std::sqrt(cost_after);
  if (q.corners.shift(s.plane, initial) <= params.max_shift_px && cost_after < cost_before &&
      s.gain > 0.5 && s.gain < 2.0) {
    fit.plane = s.plane;
    fit.accepted = true;
  }
  return fit;
}

std::size_t face_pixels(ImageView<const std::uint8_t> classes, Rect roi, std::uint8_t cls,
                        int edge_px, std::span<std::int32_t> scratch, std::span<PixelPos> out) {
  constexpr std::uint8_t kUnknown = 0xFF;
  const int W = classes.width(), H = classes.height();
  if (scratch.size() < face_pixels_scratch(W, H)) return 0;
  // The face's extent along each row: a plane facet projects to a convex
  // polygon, so an unknown pixel between two of its pixels on the same row
  // lies on it. Those are the matchers' holes on a steep face (false
  // occlusions, bands of no match): leaving them out cuts the face into
  // pieces whose photometric optimum wanders by degrees.
  std::int32_t* row_lo = scratch.data();
  std::int32_t* row_hi = row_lo + H;
  for (int j = 0; j < H; ++j) row_lo[j] = W, row_hi[j] = -1;
  for (int j = 0; j < H; ++j)
    for (int i = 0; i < W; ++i)
      if (classes(i, j) == cls) {
        row_lo[j] = std::min(row_lo[j], i);
        row_hi[j] = std::max(row_hi[j], i);
      }
  // A pixel whose box misses the face's bounding box holds none of it and
  // is not enclosed: the scan covers that box grown by edge_px only.
  int i_lo = W, i_hi = -1, j_lo = H, j_hi = -1;
  for (int j = 0; j < H; ++j)
    if (row_hi[j] >= 0) {
      i_lo = std::min(i_lo, row_lo[j]), i_hi = std::max(i_hi, row_hi[j]);
      j_lo = std::min(j_lo, j), j_hi = j;
    }
  const int i0 = std::max(0, i_lo - edge_px), i1 = std::min(W - 1, i_hi + edge_px);
  const int j0 = std::max(0, j_lo - edge_px), j1 = std::min(H - 1, j_hi + edge_px);
  std::size_t n = 0;
  const int box = (2 * edge_px + 1) * (2 * edge_px + 1);
  for (int j = j0; j <= j1 && n < out.size(); ++j)
    for (int i = i0; i <= i1 && n < out.size(); ++i) {
      const std::uint8_t c0 = classes(i, j);
      if (c0 != cls && c0 != kUnknown) continue;
      if (i < edge_px || j < edge_px || i + edge_px >= W || j + edge_px >= H) continue;
      const bool enclosed = i >= row_lo[j] && i <= row_hi[j];
      int same = 0;
      bool other = false;
      for (int dj = -edge_px; dj <= edge_px && !other; ++dj)
        for (int di = -edge_px; di <= edge_px; ++di) {
          const std::uint8_t c = classes(i + di, j + dj);
          if (c == cls)
            ++same;
          else if (c != kUnknown) {
            other = true;
            break;
          }
        }
      if (other || (!enclosed && 2 * same < box)) continue;
      out[n++] =
          PixelPos{static_cast<std::int16_t>(roi.x + i), static_cast<std::int16_t>(roi.y + j)};
    }
  return n;
}

}  // namespace petra
