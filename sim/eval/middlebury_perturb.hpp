// A reproducible photometric difference between the two cameras, applied to
// the right view of a Middlebury pair to measure how much a matcher depends
// on the views having the same gain, offset and vignetting:
//   v' = clamp(round((gain * v + offset) * (1 - vignetting * r^2) + sigma * n))
// r = distance from the image centre over the half diagonal (0..1), n a
// standard normal sample from a seeded std::mt19937 (Box-Muller, so the
// sequence is the same with any standard library).
#pragma once

#include <cstdint>
#include <string>

#include "algo/core/result.hpp"
#include "sim/io/image_io.hpp"

namespace petra::eval {

struct Perturbation {
  double gain = 1.0;
  double offset = 0.0;       // gray levels
  double noise_sigma = 0.0;  // gray levels
  double vignetting = 0.0;   // relative darkening at the corners, 0..1
  std::uint32_t seed = 1;
  bool active() const {
    return gain != 1.0 || offset != 0.0 || noise_sigma != 0.0 || vignetting != 0.0;
  }
};

// The issue-21 camera difference: gain 0.82, offset +12, noise sigma 2.
inline constexpr Perturbation kCameraDifference{0.82, 12.0, 2.0, 0.0, 1};

// Checks the ranges (gain in (0, 4], |offset| <= 255, sigma in [0, 64],
// vignetting in [0, 1)); the error names the field.
Status validate(const Perturbation& p);

// Applies `p` to `image` in place (callers validate first).
void perturb(io::GrayImage& image, const Perturbation& p);

// "gain,offset,sigma[,seed[,vignetting]]", e.g. "0.82,12,2".
Result<Perturbation> parse_perturbation(const std::string& text);

}  // namespace petra::eval
