#include "sim/calib/chessboard_corners.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <optional>

#include "sim/calib/chessboard_grid.hpp"
#include "sim/calib/corner_subpix.hpp"
#include "sim/calib/image_sampling.hpp"
#include "sim/calib/xcorner_candidates.hpp"

namespace petra::calib {

namespace {

using Vec2 = Eigen::Vector2d;

// A partly known grid of corner positions, cell (i, j) at i + j*w.
struct Grid {
  int w = 0, h = 0;
  std::vector<std::optional<Vec2>> p;

  std::optional<Vec2>& at(int i, int j) { return p[static_cast<std::size_t>(j) * w + i]; }
  const std::optional<Vec2>& at(int i, int j) const {
    return p[static_cast<std::size_t>(j) * w + i];
  }
  int found() const {
    return static_cast<int>(
        std::count_if(p.begin(), p.end(), [](const auto& c) { return c.has_value(); }));
  }
  Grid transposed() const {
    Grid t{h, w, std::vector<std::optional<Vec2>>(p.size())};
    for (int j = 0; j < h; ++j)
      for (int i = 0; i < w; ++i) t.at(j, i) = at(i, j);
    return t;
  }
};

struct Images {
  ImageView<const float> smooth, raw;
  int ring_radius;
  double min_contrast;
};

// Homography grid -> image by DLT on normalised coordinates.
std::optional<Eigen::Matrix3d> fit_homography(const std::vector<Vec2>& g,
                                              const std::vector<Vec2>& x) {
  const int n = static_cast<int>(g.size());
  if (n < 4) return std::nullopt;
  auto normaliser = [](const std::vector<Vec2>& pts) {
    Vec2 mean = Vec2::Zero();
    for (const Vec2& q : pts) mean += q;
    mean /= static_cast<double>(pts.size());
    double spread = 0;
    for (const Vec2& q : pts) spread += (q - mean).norm();
    spread = spread > 0 ? spread / static_cast<double>(pts.size()) : 1.0;
    Eigen::Matrix3d t = Eigen::Matrix3d::Identity();
    t(0, 0) = t(1, 1) = 1.0 / spread;
    t(0, 2) = -mean.x() / spread;
    t(1, 2) = -mean.y() / spread;
    return t;
  };
  const Eigen::Matrix3d tg = normaliser(g), tx = normaliser(x);
  Eigen::MatrixXd a(2 * n, 9);
  for (int k = 0; k < n; ++k) {
    const Eigen::Vector3d s = tg * g[static_cast<std::size_t>(k)].homogeneous();
    const Eigen::Vector3d d = tx * x[static_cast<std::size_t>(k)].homogeneous();
    a.row(2 * k) << 0, 0, 0, -s.x(), -s.y(), -1, d.y() * s.x(), d.y() * s.y(), d.y();
    a.row(2 * k + 1) << s.x(), s.y(), 1, 0, 0, 0, -d.x() * s.x(), -d.x() * s.y(), -d.x();
  }
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(a, Eigen::ComputeFullV);
  const Eigen::VectorXd hv = svd.matrixV().col(8);
  Eigen::Matrix3d hn;
  hn << hv(0), hv(1), hv(2), hv(3), hv(4), hv(5), hv(6), hv(7), hv(8);
  const Eigen::Matrix3d hm = tx.inverse() * hn * tg;
  if (!hm.allFinite()) return std::nullopt;
  return hm;
}

Vec2 apply(const Eigen::Matrix3d& hm, double i, double j) {
  const Eigen::Vector3d q = hm * Eigen::Vector3d(i, j, 1.0);
  return q.hnormalized();
}

// Local homography from known cells near (i, j) (which may lie outside the grid).
std::optional<Eigen::Matrix3d> local_homography(const Grid& grid, int i, int j) {
  for (int radius = 2; radius <= 4; ++radius) {
    std::vector<Vec2> g, x;
    int imin = 1 << 20, imax = -(1 << 20), jmin = 1 << 20, jmax = -(1 << 20);
    for (int jj = std::max(0, j - radius); jj <= std::min(grid.h - 1, j + radius); ++jj)
      for (int ii = std::max(0, i - radius); ii <= std::min(grid.w - 1, i + radius); ++ii)
        if (grid.at(ii, jj)) {
          g.emplace_back(ii, jj);
          x.push_back(*grid.at(ii, jj));
          imin = std::min(imin, ii);
          imax = std::max(imax, ii);
          jmin = std::min(jmin, jj);
          jmax = std::max(jmax, jj);
        }
    if (g.size() >= 6 && imax > imin && jmax > jmin) return fit_homography(g, x);
  }
  return std::nullopt;
}

// The four squares around a corner at p, centred at p + (+-a +-b)/2 for the
// grid steps a, b, must alternate: a board corner has two dark and two bright
// squares on its diagonals. A junction just outside the board (outer square,
// white margin, dark background) can pass the ring test but not this.
bool squares_alternate(const Images& im, const Vec2& p, const Vec2& a, const Vec2& b) {
  double v[4];
  const Vec2 c[4] = {p + 0.5 * (a + b), p - 0.5 * (a + b), p + 0.5 * (a - b), p - 0.5 * (a - b)};
  for (int k = 0; k < 4; ++k) {
    if (!im.smooth.in_bounds(static_cast<int>(c[k].x()), static_cast<int>(c[k].y()))) return false;
    v[k] = sample_bilinear(im.smooth, c[k].x(), c[k].y());
  }
  const double thr = 0.5 * im.min_contrast;
  return std::min(v[0], v[1]) - std::max(v[2], v[3]) > thr ||
         std::min(v[2], v[3]) - std::max(v[0], v[1]) > thr;
}

// Grid steps at (i, j) from its neighbours (forward where possible).
bool local_steps(const Grid& g, int i, int j, Vec2& a, Vec2& b) {
  const Vec2& p = *g.at(i, j);
  if (i + 1 < g.w && g.at(i + 1, j))
    a = *g.at(i + 1, j) - p;
  else if (i > 0 && g.at(i - 1, j))
    a = p - *g.at(i - 1, j);
  else
    return false;
  if (j + 1 < g.h && g.at(i, j + 1))
    b = *g.at(i, j + 1) - p;
  else if (j > 0 && g.at(i, j - 1))
    b = p - *g.at(i, j - 1);
  else
    return false;
  return true;
}

// Drops corners whose surrounding squares do not alternate, then lines of the
// grid left empty at its border.
void drop_false_corners(const Images& im, Grid& g) {
  std::vector<std::size_t> bad;
  for (int j = 0; j < g.h; ++j)
    for (int i = 0; i < g.w; ++i) {
      if (!g.at(i, j)) continue;
      Vec2 a, b;
      if (!local_steps(g, i, j, a, b) || !squares_alternate(im, *g.at(i, j), a, b))
        bad.push_back(static_cast<std::size_t>(j) * g.w + i);
    }
  for (std::size_t k : bad) g.p[k].reset();
  auto column_empty = [&](int i) {
    for (int j = 0; j < g.h; ++j)
      if (g.at(i, j)) return false;
    return true;
  };
  auto row_empty = [&](int j) {
    for (int i = 0; i < g.w; ++i)
      if (g.at(i, j)) return false;
    return true;
  };
  int i0 = 0, i1 = g.w - 1, j0 = 0, j1 = g.h - 1;
  while (i0 <= i1 && column_empty(i0)) ++i0;
  while (i1 >= i0 && column_empty(i1)) --i1;
  while (j0 <= j1 && row_empty(j0)) ++j0;
  while (j1 >= j0 && row_empty(j1)) --j1;
  if (i0 > i1 || j0 > j1) {
    g = Grid{};
    return;
  }
  Grid t{i1 - i0 + 1, j1 - j0 + 1, {}};
  t.p.resize(static_cast<std::size_t>(t.w) * t.h);
  for (int j = 0; j < t.h; ++j)
    for (int i = 0; i < t.w; ++i) t.at(i, j) = g.at(i + i0, j + j0);
  g = std::move(t);
}

// A corner the candidates missed: refine from the prediction and accept it
// only if it stays near the prediction and looks like an X-corner.
std::optional<Vec2> verify_predicted(const Images& im, const Grid& grid, int i, int j) {
  const auto hm = local_homography(grid, i, j);
  if (!hm) return std::nullopt;
  const Vec2 pred = apply(*hm, i, j);
  const double spacing =
      std::min((apply(*hm, i + 1, j) - pred).norm(), (apply(*hm, i, j + 1) - pred).norm());
  if (!(spacing > 6.0)) return std::nullopt;
  SubpixOptions sp;
  sp.half_window = std::clamp(static_cast<int>(0.3 * spacing), 2, 5);
  auto refined = refine_corner(im.raw, pred, sp);
  if (!refined || (*refined - pred).norm() > 0.3 * spacing) return std::nullopt;
  const double r = std::min<double>(im.ring_radius, 0.35 * spacing);
  if (!analyse_ring(im.smooth, *refined, r, im.min_contrast).is_xcorner) return std::nullopt;
  const Vec2 a = apply(*hm, i + 1, j) - pred, b = apply(*hm, i, j + 1) - pred;
  if (!squares_alternate(im, *refined, a, b)) return std::nullopt;
  return *refined;
}

void fill_holes(const Images& im, Grid& grid) {
  for (bool changed = true; changed;) {
    changed = false;
    for (int j = 0; j < grid.h; ++j)
      for (int i = 0; i < grid.w; ++i)
        if (!grid.at(i, j))
          if (auto c = verify_predicted(im, grid, i, j)) {
            grid.at(i, j) = *c;
            changed = true;
          }
  }
}

// Adds one line of corners on a side when every corner of it verifies.
// side: 0 = before i = 0, 1 = after i = w-1, 2 = before j = 0, 3 = after j = h-1.
bool extend(const Images& im, Grid& grid, int side) {
  const bool along_i = side < 2;
  const int len = along_i ? grid.h : grid.w;
  std::vector<Vec2> line;
  for (int k = 0; k < len; ++k) {
    const int i = side == 0 ? -1 : side == 1 ? grid.w : k;
    const int j = side == 2 ? -1 : side == 3 ? grid.h : k;
    auto c = verify_predicted(im, grid, i, j);
    if (!c) return false;
    line.push_back(*c);
  }
  Grid g{grid.w + (along_i ? 1 : 0), grid.h + (along_i ? 0 : 1), {}};
  g.p.resize(static_cast<std::size_t>(g.w) * g.h);
  const int di = side == 0 ? 1 : 0, dj = side == 2 ? 1 : 0;
  for (int j = 0; j < grid.h; ++j)
    for (int i = 0; i < grid.w; ++i) g.at(i + di, j + dj) = grid.at(i, j);
  for (int k = 0; k < len; ++k) {
    const int i = side == 0 ? 0 : side == 1 ? g.w - 1 : k;
    const int j = side == 2 ? 0 : side == 3 ? g.h - 1 : k;
    g.at(i, j) = line[static_cast<std::size_t>(k)];
  }
  grid = std::move(g);
  return true;
}

// Grows the grid towards cols x rows (first axis along cols). True when complete.
bool complete(const Images& im, Grid& grid, int cols, int rows) {
  fill_holes(im, grid);
  for (bool grew = true; grew && (grid.w < cols || grid.h < rows);) {
    grew = false;
    for (int side = 0; side < 4; ++side) {
      if (side < 2 ? grid.w >= cols : grid.h >= rows) continue;
      if (extend(im, grid, side)) {
        grew = true;
        fill_holes(im, grid);
      }
    }
  }
  return grid.w == cols && grid.h == rows && grid.found() == cols * rows;
}

double cross(const Vec2& a, const Vec2& b) {
  return a.x() * b.y() - a.y() * b.x();
}

// Mean intensity inside the square whose top-left corner is (i, j).
double square_intensity(const Images& im, const Grid& g, int i, int j) {
  const Vec2 c = 0.25 * (*g.at(i, j) + *g.at(i + 1, j) + *g.at(i, j + 1) + *g.at(i + 1, j + 1));
  return sample_bilinear(im.smooth, c.x(), c.y());
}

Grid rotated180(const Grid& g) {
  Grid r = g;
  for (int j = 0; j < g.h; ++j)
    for (int i = 0; i < g.w; ++i) r.at(i, j) = g.at(g.w - 1 - i, g.h - 1 - j);
  return r;
}

Grid flipped_j(const Grid& g) {
  Grid r = g;
  for (int j = 0; j < g.h; ++j)
    for (int i = 0; i < g.w; ++i) r.at(i, j) = g.at(i, g.h - 1 - j);
  return r;
}

// Orders a complete grid by the convention in the header.
Grid canonical_order(const Images& im, Grid g, bool& unique) {
  Vec2 ui = Vec2::Zero(), uj = Vec2::Zero();
  for (int j = 0; j + 1 < g.h; ++j)
    for (int i = 0; i + 1 < g.w; ++i) {
      ui += *g.at(i + 1, j) - *g.at(i, j);
      uj += *g.at(i, j + 1) - *g.at(i, j);
    }
  if (cross(ui, uj) < 0) g = flipped_j(g);
  unique = (g.w + g.h) % 2 == 1;
  if (unique) {
    // 180 degrees changes the colour of the first square: make it the dark one.
    if (square_intensity(im, g, 0, 0) > square_intensity(im, g, 1, 0)) g = rotated180(g);
    return g;
  }
  std::vector<Grid> options{g, rotated180(g)};
  if (g.w == g.h) {
    // A square board may also be turned by 90 degrees (transpose + flip keeps handedness).
    Grid t = flipped_j(g.transposed());
    options.push_back(t);
    options.push_back(rotated180(t));
  }
  std::size_t best = 0;
  for (std::size_t k = 1; k < options.size(); ++k)
    if (options[k].p[0]->sum() < options[best].p[0]->sum()) best = k;
  return options[best];
}

struct Attempt {
  std::optional<ChessboardCorners> corners;
  int seen_w = 0, seen_h = 0, seen_found = 0;
  bool too_big = false;
};

Attempt try_radius(const Images& im, const ChessboardOptions& opt) {
  Attempt out;
  XCornerOptions xo;
  xo.ring_radius_px = im.ring_radius;
  xo.expected_corners = opt.cols * opt.rows;
  xo.min_contrast = opt.min_contrast;
  const std::vector<XCorner> cands = find_xcorners(im.smooth, im.raw, xo);
  const GridLabelling lab = label_grid(cands, im.smooth, opt.min_contrast);
  if (lab.found() < 4) return out;
  Grid grid{lab.width, lab.height, {}};
  grid.p.resize(lab.cell.size());
  for (std::size_t k = 0; k < lab.cell.size(); ++k)
    if (lab.cell[k] >= 0) grid.p[k] = cands[static_cast<std::size_t>(lab.cell[k])].uv;
  drop_false_corners(im, grid);
  if (grid.found() < 4) return out;
  out.seen_w = grid.w;
  out.seen_h = grid.h;
  out.seen_found = grid.found();
  const int big = std::max(opt.cols, opt.rows), small = std::min(opt.cols, opt.rows);
  if (std::max(grid.w, grid.h) > big || std::min(grid.w, grid.h) > small) {
    out.too_big = true;
    return out;
  }
  // Try the grid's first axis along cols, then along rows.
  for (int pass = 0; pass < 2; ++pass) {
    Grid g = pass == 0 ? grid : grid.transposed();
    if (g.w > opt.cols || g.h > opt.rows) continue;
    if (pass == 1 && opt.cols == opt.rows) break;
    if (!complete(im, g, opt.cols, opt.rows)) {
      if (g.found() > out.seen_found) {
        out.seen_w = g.w;
        out.seen_h = g.h;
        out.seen_found = g.found();
      }
      continue;
    }
    bool unique = true;
    g = canonical_order(im, g, unique);
    ChessboardCorners c;
    c.cols = opt.cols;
    c.rows = opt.rows;
    c.orientation_unique = unique;
    for (const auto& q : g.p) c.uv.push_back(*q);
    out.corners = c;
    return out;
  }
  return out;
}

// Median neighbour distance, and the smallest distance from a corner to a
// grid line not through it (the height of the thinnest square, which is what
// must stay outside the refinement window).
double median_spacing(const ChessboardCorners& c, double& min_height) {
  std::vector<double> d;
  min_height = 1e300;
  for (int j = 0; j + 1 < c.rows; ++j)
    for (int i = 0; i + 1 < c.cols; ++i) {
      const Vec2& p = c.uv[static_cast<std::size_t>(j * c.cols + i)];
      const Vec2 a = c.uv[static_cast<std::size_t>(j * c.cols + i + 1)] - p;
      const Vec2 b = c.uv[static_cast<std::size_t>((j + 1) * c.cols + i)] - p;
      d.push_back(a.norm());
      d.push_back(b.norm());
      const double area = std::abs(cross(a, b));
      min_height = std::min({min_height, area / a.norm(), area / b.norm()});
    }
  std::sort(d.begin(), d.end());
  return d[d.size() / 2];
}

}  // namespace

Result<ChessboardCorners> detect_chessboard(ConstGray8View image, const ChessboardOptions& opt) {
  if (opt.cols < 2 || opt.rows < 2 || opt.cols > 100 || opt.rows > 100)
    return Error::make(Errc::invalid_argument, "board: %dx%d inner corners (each must be 2..100)",
                       opt.cols, opt.rows);
  if (image.width() < 32 || image.height() < 32)
    return Error::make(Errc::invalid_argument, "board: image %dx%d too small", image.width(),
                       image.height());
  const io::FloatImage smooth = smooth_binomial5(image);
  const io::FloatImage raw = to_float(image);
  const int auto_r = std::clamp(
      static_cast<int>(std::lround(std::min(image.width(), image.height()) / 96.0)), 3, 12);
  std::vector<int> radii;
  if (opt.ring_radius_px > 0)
    radii = {opt.ring_radius_px};
  else
    radii = {auto_r, std::max(3, static_cast<int>(std::lround(auto_r * 0.6))),
             static_cast<int>(std::lround(auto_r * 1.6))};
  Attempt best;
  for (std::size_t k = 0; k < radii.size(); ++k) {
    if (k > 0 && radii[k] == radii[k - 1]) continue;
    Images im{smooth.view(), raw.view(), radii[k], opt.min_contrast};
    Attempt a = try_radius(im, opt);
    if (a.corners) {
      ChessboardCorners c = *a.corners;
      double min_height = 0;
      c.square_px = median_spacing(c, min_height);
      // Final positions: a window of at most 11x11 px that keeps the other grid
      // lines out. Wider windows average more noise on synthetic boards but on
      // real ones they reach the board's border or frame where the outer squares
      // are cut short (OpenCV's set: per-view RMS up to 0.5 px with 23x23
      // windows, uniformly 0.2 px with 11x11).
      SubpixOptions sp;
      sp.half_window = opt.subpix_half_window > 0
                           ? opt.subpix_half_window
                           : std::clamp(static_cast<int>(0.5 * min_height), 2, 5);
      c.subpix_half_window = sp.half_window;
      for (Vec2& p : c.uv)
        if (auto r = refine_corner(raw.view(), p, sp); r && (*r - p).norm() < 0.25 * min_height)
          p = *r;
      return c;
    }
    if (a.seen_found > best.seen_found) best = a;
  }
  if (best.seen_found == 0)
    return Error::make(Errc::no_solution, "board not found: no chessboard pattern in the image");
  if (best.too_big)
    return Error::make(Errc::no_solution,
                       "board not found: %dx%d inner corners visible, more than the %dx%d expected",
                       std::max(best.seen_w, best.seen_h), std::min(best.seen_w, best.seen_h),
                       opt.cols, opt.rows);
  return Error::make(Errc::no_solution,
                     "board not found: %d corners in a %dx%d grid visible, expected %dx%d (hidden, "
                     "cut off or another size)",
                     best.seen_found, best.seen_w, best.seen_h, opt.cols, opt.rows);
}

}  // namespace petra::calib
