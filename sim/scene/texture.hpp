// Solid (3-D) procedural albedo: a function of the world point only, so the
// same surface point has the same albedo in both views. Detail finer than
// the pixel footprint is faded out (procedural anti-aliasing), so distant
// ground does not alias.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>

namespace petra::sim {

// Lattice hashing table: a random permutation of 0..255, stored twice.
using Permutation = std::array<std::uint8_t, 512>;
Permutation make_permutation(std::uint64_t seed);

// Gradient noise (Perlin-style, quintic fade) on the integer lattice, in
// about [-1, 1], zero on lattice points; period 256 cells. Lattice gradients
// come from the permutation.
double gradient_noise(const Eigen::Vector3d& p, const Permutation& perm);

// A surface recipe: mean albedo, fractal contrast and spots.
struct TextureRecipe {
  double mean_albedo = 0.5;
  double fractal_contrast = 0.2;  // 1-sigma relative albedo variation of the fractal
  double largest_mm = 200;        // fractal wavelengths from largest_mm ...
  double finest_mm = 1.5;         // ... down to finest_mm, halving
  double persistence = 0.7;       // amplitude ratio between successive octaves
  double spot_scale_mm = 7;       // pebble-like dark and light spots (0: none)
  double spot_contrast = 0.3;
  double vein_scale_mm = 0;  // light veins (0: none)
  double vein_contrast = 0.25;
  Permutation perm{};  // from make_permutation(seed)
};

// Albedo at world point p for a pixel footprint of `footprint_mm` (the size
// of one pixel on the surface); clamped to [0.02, 1].
double albedo(const TextureRecipe& recipe, const Eigen::Vector3d& p, double footprint_mm);

}  // namespace petra::sim
