// Deterministic random numbers for the scene simulator. Every draw is built
// from the raw 64-bit output here (never std:: distributions, whose results
// are implementation-defined), so a seed gives the same scene on every
// platform and library version.
//   SplitMix64 seeds and derives independent streams; xoshiro256** draws.
#pragma once

#include <cstdint>

namespace petra::sim {

// One step of SplitMix64: a strong 64-bit mix, also used as a hash.
std::uint64_t splitmix64(std::uint64_t& state);
// Stateless mix of one value (SplitMix64 finaliser).
std::uint64_t mix64(std::uint64_t x);

// A standard normal value that depends only on (key, index): per-pixel sensor
// noise that is the same whichever part of an image is rendered.
double hashed_normal(std::uint64_t key, std::uint64_t index);

class Rng {
 public:
  // A stream identified by (seed, stream): different streams of one seed are
  // independent, so adding draws to one part of the scene never shifts another.
  Rng(std::uint64_t seed, std::uint64_t stream);

  std::uint64_t next();
  // Uniform in [0, 1) with 53 random bits.
  double uniform();
  // Uniform in [lo, hi).
  double uniform(double lo, double hi);
  // Uniform integer in [lo, hi] (inclusive), unbiased (rejection).
  int integer(int lo, int hi);
  // Standard normal (Box-Muller; the spare value is kept for the next call).
  double normal();
  bool coin() { return (next() >> 63) != 0; }

 private:
  std::uint64_t s_[4];
  bool have_spare_ = false;
  double spare_ = 0.0;
};

}  // namespace petra::sim
