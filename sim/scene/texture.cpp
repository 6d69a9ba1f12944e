#include "sim/scene/texture.hpp"

#include <algorithm>
#include <cmath>

#include "sim/scene/rng.hpp"

namespace petra::sim {

namespace {

// Perlin's 12 edge-midpoint gradients, padded to 16 so a 4-bit index picks
// one without a modulo (a table, not a switch: the index is random).
constexpr double kGrad[16][3] = {
    {1, 1, 0}, {-1, 1, 0}, {1, -1, 0}, {-1, -1, 0}, {1, 0, 1}, {-1, 0, 1}, {1, 0, -1}, {-1, 0, -1},
    {0, 1, 1}, {0, -1, 1}, {0, 1, -1}, {0, -1, -1}, {1, 1, 0}, {-1, 1, 0}, {0, -1, 1}, {0, -1, -1}};

inline double grad(unsigned h, double x, double y, double z) {
  const double* g = kGrad[h & 15];
  return g[0] * x + g[1] * y + g[2] * z;
}

double fade(double t) {
  return t * t * t * (t * (t * 6 - 15) + 10);
}
double lerp(double a, double b, double t) {
  return a + t * (b - a);
}

double smoothstep(double e0, double e1, double x) {
  const double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
  return t * t * (3 - 2 * t);
}

// Weight of detail of wavelength `lambda_mm` at a pixel footprint: full above
// three footprints, none below 1.5 (the renderer samples at half a pixel).
double detail_weight(double lambda_mm, double footprint_mm) {
  return std::clamp(lambda_mm / (1.5 * footprint_mm) - 1.0, 0.0, 1.0);
}

// A fixed orthonormal rotation between octaves so lattice directions do not
// line up from one octave to the next.
Eigen::Vector3d twist(const Eigen::Vector3d& p) {
  return {0.80 * p.y() + 0.60 * p.z(), -0.80 * p.x() + 0.36 * p.y() - 0.48 * p.z(),
          -0.60 * p.x() - 0.48 * p.y() + 0.64 * p.z()};
}

}  // namespace

Permutation make_permutation(std::uint64_t seed) {
  Permutation p{};
  for (int i = 0; i < 256; ++i) p[static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(i);
  Rng rng(seed, 0x7e47u);
  for (int i = 255; i > 0; --i) {  // Fisher-Yates
    const int j = rng.integer(0, i);
    std::swap(p[static_cast<std::size_t>(i)], p[static_cast<std::size_t>(j)]);
  }
  for (std::size_t i = 0; i < 256; ++i) p[i + 256] = p[i];
  return p;
}

double gradient_noise(const Eigen::Vector3d& p, const Permutation& perm) {
  const double fx = std::floor(p.x()), fy = std::floor(p.y()), fz = std::floor(p.z());
  // Wrap the cell to 0..255 (two's complement keeps negative cells consistent).
  const auto ix = static_cast<std::size_t>(static_cast<std::int64_t>(fx) & 255);
  const auto iy = static_cast<std::size_t>(static_cast<std::int64_t>(fy) & 255);
  const auto iz = static_cast<std::size_t>(static_cast<std::int64_t>(fz) & 255);
  const double x = p.x() - fx, y = p.y() - fy, z = p.z() - fz;
  const double u = fade(x), v = fade(y), w = fade(z);
  const std::size_t a = perm[ix] + iy, b = perm[ix + 1] + iy;
  const std::size_t aa = perm[a] + iz, ab = perm[a + 1] + iz;
  const std::size_t ba = perm[b] + iz, bb = perm[b + 1] + iz;
  const double x00 = lerp(grad(perm[aa], x, y, z), grad(perm[ba], x - 1, y, z), u);
  const double x10 = lerp(grad(perm[ab], x, y - 1, z), grad(perm[bb], x - 1, y - 1, z), u);
  const double x01 = lerp(grad(perm[aa + 1], x, y, z - 1), grad(perm[ba + 1], x - 1, y, z - 1), u);
  const double x11 =
      lerp(grad(perm[ab + 1], x, y - 1, z - 1), grad(perm[bb + 1], x - 1, y - 1, z - 1), u);
  return lerp(lerp(x00, x10, v), lerp(x01, x11, v), w);
}

double albedo(const TextureRecipe& r, const Eigen::Vector3d& p, double footprint_mm) {
  // Fractal sum, normalised so the full-detail sum has unit standard
  // deviation (gradient noise has sigma ~0.22); faded octaves lower the
  // variance, as blur does.
  double sum = 0, norm = 0, amp = 1;
  Eigen::Vector3d q = p;
  double shift = 0;
  for (double lambda = r.largest_mm; lambda >= r.finest_mm; lambda *= 0.5, amp *= r.persistence) {
    norm += amp * amp;
    const double w = detail_weight(lambda, footprint_mm);
    // Each octave is rotated and shifted so its lattice does not line up with the others.
    shift += 37.17;
    if (w > 0)
      sum += w * amp * gradient_noise(q / lambda + Eigen::Vector3d::Constant(shift), r.perm);
    q = twist(q);
  }
  double a = 1.0 + r.fractal_contrast * sum / (0.22 * std::sqrt(norm));
  if (r.spot_scale_mm > 0) {
    // Pebbles: dark where one noise field is high, light where it is low.
    const double wd = detail_weight(r.spot_scale_mm, footprint_mm);
    if (wd > 0) {
      const double n =
          gradient_noise(p / r.spot_scale_mm + Eigen::Vector3d(11.3, 7.9, 3.1), r.perm);
      a *= 1.0 - wd * r.spot_contrast * smoothstep(0.26, 0.40, n);
      a *= 1.0 + wd * r.spot_contrast * smoothstep(0.30, 0.44, -n);
    }
  }
  if (r.vein_scale_mm > 0) {
    const double wv = detail_weight(0.1 * r.vein_scale_mm, footprint_mm);
    if (wv > 0) {
      const double ridge =
          1.0 - std::abs(gradient_noise(p / r.vein_scale_mm + Eigen::Vector3d(171.1, 143.7, 119.3),
                                        r.perm));
      a *= 1.0 + wv * r.vein_contrast * smoothstep(0.92, 0.97, ridge);
    }
  }
  return std::clamp(r.mean_albedo * a, 0.02, 1.0);
}

}  // namespace petra::sim
