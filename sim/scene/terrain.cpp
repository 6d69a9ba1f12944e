#include "sim/scene/terrain.hpp"

#include <algorithm>
#include <cmath>

#include "sim/scene/rng.hpp"
#include "sim/scene/texture.hpp"

namespace petra::sim {

namespace {

constexpr double kHalfExtentMm = 960;                // grid half side
constexpr double kFadeInMm = 700, kFadeOutMm = 900;  // relief fades out between these radii
constexpr int kOctaves = 6;                          // wavelengths 256 .. 8 mm
constexpr double kLargestMm = 256, kPersistence = 0.55;
constexpr std::uint64_t kStreamTerrain = 21;

double fade_weight(double r) {
  const double u = std::clamp((r - kFadeInMm) / (kFadeOutMm - kFadeInMm), 0.0, 1.0);
  return 1.0 - u * u * (3 - 2 * u);
}

double raw_fractal(const Permutation& perm, double x, double y) {
  double sum = 0, amp = 1, lambda = kLargestMm;
  for (int k = 0; k < kOctaves; ++k) {
    // A different plane of the solid noise per octave decorrelates them.
    sum +=
        amp * gradient_noise({x / lambda + 17.3 * k, y / lambda + 31.7 * k, 0.5 + 7.1 * k}, perm);
    amp *= kPersistence;
    lambda *= 0.5;
  }
  return sum;
}

// Catmull-Rom weights at fraction f.
void catmull_rom(double f, double w[4]) {
  const double f2 = f * f, f3 = f2 * f;
  w[0] = 0.5 * (-f3 + 2 * f2 - f);
  w[1] = 0.5 * (3 * f3 - 5 * f2 + 2);
  w[2] = 0.5 * (-3 * f3 + 4 * f2 + f);
  w[3] = 0.5 * (f3 - f2);
}

// Their derivatives.
void catmull_rom_slopes(double f, double dw[4]) {
  const double f2 = f * f;
  dw[0] = 0.5 * (-3 * f2 + 4 * f - 1);
  dw[1] = 0.5 * (9 * f2 - 10 * f);
  dw[2] = 0.5 * (-9 * f2 + 8 * f + 1);
  dw[3] = 0.5 * (3 * f2 - 2 * f);
}

// The relief's height at (x, y) and, with kSlope, its gradient into *g (the
// ray march asks the height alone, most of the scene's time).
template <bool kSlope>
double fractal_height(const Terrain& t, double x, double y, Eigen::Vector2d* g) {
  const double gx = (x - t.centre.x() + kHalfExtentMm) / t.step_mm;
  const double gy = (y - t.centre.y() + kHalfExtentMm) / t.step_mm;
  const int i = static_cast<int>(std::floor(gx)), j = static_cast<int>(std::floor(gy));
  if constexpr (kSlope) g->setZero();
  if (i < 1 || j < 1 || i + 2 >= t.n || j + 2 >= t.n) return 0.0;  // faded out there
  double wx[4], wy[4], dwx[4], dwy[4];
  catmull_rom(gx - i, wx);
  catmull_rom(gy - j, wy);
  if constexpr (kSlope) {
    catmull_rom_slopes(gx - i, dwx);
    catmull_rom_slopes(gy - j, dwy);
  }
  double h = 0, hx = 0, hy = 0;
  for (int b = 0; b < 4; ++b) {
    const float* row = &t.grid[static_cast<std::size_t>(j - 1 + b) * t.n + (i - 1)];
    double r = 0, rx = 0;
    for (int a = 0; a < 4; ++a) {
      r += wx[a] * double(row[a]);
      if constexpr (kSlope) rx += dwx[a] * double(row[a]);
    }
    h += wy[b] * r;
    if constexpr (kSlope) {
      hx += wy[b] * rx;
      hy += dwy[b] * r;
    }
  }
  if constexpr (kSlope) *g = Eigen::Vector2d(hx, hy) / t.step_mm;
  return h;
}

struct Pebble {
  double x = 0, y = 0, radius = 0, height = 0;
};

// The pebble of cell (cx, cy) into p, if the cell has one.
bool cell_pebble(const Terrain& t, double cx, double cy, Pebble& p) {
  if (t.pebble_chance <= 0) return false;
  const auto ix = static_cast<std::uint64_t>(static_cast<std::int64_t>(cx));
  const auto iy = static_cast<std::uint64_t>(static_cast<std::int64_t>(cy));
  std::uint64_t state = t.pebble_key ^ mix64(ix * 0x9E3779B97F4A7C15ull + iy);
  auto u = [&state] { return static_cast<double>(splitmix64(state) >> 11) * 0x1.0p-53; };
  if (u() >= t.pebble_chance) return false;
  const double a = 2.0 + 5.0 * u();  // radius 2..7 mm
  p.radius = a;
  p.x = cx * kPebbleCellMm + a + u() * (kPebbleCellMm - 2 * a);
  p.y = cy * kPebbleCellMm + a + u() * (kPebbleCellMm - 2 * a);
  const double r2 = std::pow(p.x - t.centre.x(), 2) + std::pow(p.y - t.centre.y(), 2);
  const double fade = r2 < kFadeInMm * kFadeInMm ? 1.0 : fade_weight(std::sqrt(r2));
  p.height = a * (0.35 + 0.25 * u()) * fade;
  return true;
}

// Pebble p's height at (x, y) and, unless null, its gradient into *g.
double bump_height(const Pebble& p, double x, double y, Eigen::Vector2d* g) {
  const double dx = x - p.x, dy = y - p.y;
  const double q = (dx * dx + dy * dy) / (p.radius * p.radius);
  if (q >= 1.0) return 0.0;
  const double s = 1.0 - q;
  if (g) *g = Eigen::Vector2d(dx, dy) * (-4.0 * p.height * s / (p.radius * p.radius));
  return p.height * s * s;
}

// The pebble of the cell holding (x, y), if any: height and gradient.
double pebble_height(const Terrain& t, double x, double y, Eigen::Vector2d* g) {
  if (g) g->setZero();
  Pebble p;
  if (!cell_pebble(t, std::floor(x / kPebbleCellMm), std::floor(y / kPebbleCellMm), p)) return 0.0;
  return bump_height(p, x, y, g);
}

// Distance along a ray with horizontal direction d from (x, y) to the edge of its pebble cell.
double to_cell_exit(double x, double y, const Eigen::Vector3d& d) {
  double best = INFINITY;
  for (int k = 0; k < 2; ++k) {
    const double p = k == 0 ? x : y, v = d[k];
    if (v == 0) continue;
    const double lo = std::floor(p / kPebbleCellMm) * kPebbleCellMm;
    best = std::min(best, ((v > 0 ? lo + kPebbleCellMm : lo) - p) / v);
  }
  return best;
}

}  // namespace

Terrain make_terrain(const World& world, std::uint64_t seed, const Eigen::Vector2d& centre) {
  Terrain t;
  t.active = world.relief_rms_mm > 0 || world.pebble_cover > 0;
  if (!t.active) return t;
  t.centre = centre;
  t.n = static_cast<int>(2 * kHalfExtentMm / t.step_mm) + 1;
  t.grid.assign(static_cast<std::size_t>(t.n) * t.n, 0.0f);
  Rng rng(seed, kStreamTerrain);
  const Permutation perm = make_permutation(rng.next());
  t.pebble_key = rng.next();
  if (world.relief_rms_mm > 0) {
    std::vector<double> raw(t.grid.size());
    double sum = 0, sum2 = 0;
    long count = 0;
    for (int j = 0; j < t.n; ++j)
      for (int i = 0; i < t.n; ++i) {
        const double x = i * t.step_mm - kHalfExtentMm, y = j * t.step_mm - kHalfExtentMm;
        const double v = raw_fractal(perm, x + centre.x(), y + centre.y());
        raw[static_cast<std::size_t>(j) * t.n + i] = v;
        if (std::hypot(x, y) < kFadeInMm) {
          sum += v;
          sum2 += v * v;
          ++count;
        }
      }
    const double mean = sum / static_cast<double>(count);
    const double sd = std::sqrt(std::max(sum2 / static_cast<double>(count) - mean * mean, 1e-12));
    // Zero mean and the chosen RMS inside the full-relief disc.
    const double scale = world.relief_rms_mm / sd;
    for (int j = 0; j < t.n; ++j)
      for (int i = 0; i < t.n; ++i) {
        const double r = std::hypot(i * t.step_mm - kHalfExtentMm, j * t.step_mm - kHalfExtentMm);
        const std::size_t k = static_cast<std::size_t>(j) * t.n + i;
        t.grid[k] = static_cast<float>((raw[k] - mean) * scale * fade_weight(r));
      }
    double lo = 0, hi = 0, slope = 0;
    for (int j = 0; j + 1 < t.n; ++j)
      for (int i = 0; i + 1 < t.n; ++i) {
        const std::size_t k = static_cast<std::size_t>(j) * t.n + i;
        lo = std::min(lo, double(t.grid[k]));
        hi = std::max(hi, double(t.grid[k]));
        slope = std::max(slope, std::hypot(double(t.grid[k + 1] - t.grid[k]),
                                           double(t.grid[k + t.n] - t.grid[k])) /
                                    t.step_mm);
      }
    // Catmull-Rom overshoots the nodes a little: widen the bounds.
    const double margin = 0.25 * (hi - lo) + 0.05;
    t.fractal_min = lo - margin;
    t.fractal_max = hi + margin;
    t.fractal_slope = 1.6 * slope + 0.01;
  }
  // Pebbles 2..7 mm in radius cover a disc of pi E[a^2] = pi 335/15 mm^2.
  const double mean_area = M_PI * 335.0 / 15.0;
  t.pebble_chance = std::min(1.0, world.pebble_cover * kPebbleCellMm * kPebbleCellMm / mean_area);
  return t;
}

double terrain_height(const Terrain& t, double x, double y, Eigen::Vector2d* gradient) {
  if (!t.active) {
    if (gradient) gradient->setZero();
    return 0.0;
  }
  Eigen::Vector2d gf, gp;
  const double h = fractal_height<true>(t, x, y, &gf) + pebble_height(t, x, y, &gp);
  if (gradient) *gradient = gf + gp;
  return h;
}

Eigen::Vector3d terrain_normal(const Terrain& t, double x, double y) {
  Eigen::Vector2d g;
  terrain_height(t, x, y, &g);
  return Eigen::Vector3d(-g.x(), -g.y(), 1.0).normalized();
}

namespace {

// Outside the relief disc the ground is the plane z = 0: where does the ray
// meet it, unless it first enters the disc? Returns the t to resume from and
// whether that t is a hit on the plane.
bool flat_shortcut(const Terrain& t, const Eigen::Vector3d& o, const Eigen::Vector3d& dir,
                   double& at, bool& hit) {
  const Eigen::Vector2d p = (o + at * dir).head<2>() - t.centre;
  const double r_out = kFadeOutMm + kPebbleCellMm;
  if (p.squaredNorm() <= r_out * r_out) return false;
  const Eigen::Vector2d d = dir.head<2>();
  const double t_plane = dir.z() < 0 ? -(o.z() + at * dir.z()) / dir.z() : double(INFINITY);
  // Entry into the disc along the ray, from the current point.
  const double a = d.squaredNorm(), b = p.dot(d), c = p.squaredNorm() - r_out * r_out;
  const double disc = b * b - a * c;
  double t_enter = INFINITY;
  if (a > 0 && disc >= 0 && b < 0) t_enter = (-b - std::sqrt(disc)) / a;
  if (t_plane <= t_enter) {
    hit = std::isfinite(t_plane);
    at += t_plane;
    return true;
  }
  at += t_enter;
  hit = false;
  return false;
}

}  // namespace

bool ray_hits_terrain(const Terrain& t, const Eigen::Vector3d& o, const Eigen::Vector3d& dir,
                      double t_min, double t_max, double& t_hit) {
  const double peb_max = t.pebble_chance > 0 ? kPebbleMaxHeightMm : 0.0;
  const double peb_slope = t.pebble_chance > 0 ? kPebbleMaxSlope : 0.0;
  const double z_top = t.fractal_max + peb_max;
  const double horiz = dir.head<2>().norm();
  double at = t_min;
  if (o.z() + at * dir.z() > z_top) {
    if (dir.z() >= 0) return false;
    at = (z_top - o.z()) / dir.z();
  }
  const double rate_f = t.fractal_slope * horiz - dir.z();  // fastest approach to the relief
  const double rate = (t.fractal_slope + peb_slope) * horiz - dir.z();
  double cell_x = NAN, cell_y = NAN;  // the pebble cell last looked up
  bool has = false;
  Pebble pebble;
  for (int it = 0; it < 2000 && at <= t_max; ++it) {
    bool plane_hit = false;
    if (flat_shortcut(t, o, dir, at, plane_hit)) {
      if (!plane_hit || at > t_max) return false;
      t_hit = at;
      return true;
    }
    const Eigen::Vector3d p = o + at * dir;
    if (p.z() > z_top + 1e-9 && dir.z() >= 0) return false;
    const double gap_f = p.z() - fractal_height<false>(t, p.x(), p.y(), nullptr);
    if (gap_f - peb_max > 0.05) {
      if (rate_f <= 0) return false;  // rising faster than any slope
      at += (gap_f - peb_max) / rate_f;
      continue;
    }
    // A cell without a pebble (or a ray outside its pebble's disc) sees the
    // relief alone until it leaves the cell: step by the relief's slope.
    const double cx = std::floor(p.x() / kPebbleCellMm), cy = std::floor(p.y() / kPebbleCellMm);
    if (cx != cell_x || cy != cell_y) {  // the march takes many steps within one cell
      cell_x = cx;
      cell_y = cy;
      has = cell_pebble(t, cx, cy, pebble);
    }
    const double gap = gap_f - (has ? bump_height(pebble, p.x(), p.y(), nullptr) : 0.0);
    if (gap < 1e-3) {
      t_hit = at;
      return at <= t_max;
    }
    if (!has && rate_f > 0) {
      at += std::min(gap / rate_f, to_cell_exit(p.x(), p.y(), dir) + 1e-3);
      continue;
    }
    if (rate <= 0) return false;
    at += gap / rate;
  }
  return false;
}

}  // namespace petra::sim
