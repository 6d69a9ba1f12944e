#include "sim/scene/rng.hpp"

#include <cmath>

namespace petra::sim {

std::uint64_t splitmix64(std::uint64_t& state) {
  state += 0x9e3779b97f4a7c15ull;
  return mix64(state);
}

std::uint64_t mix64(std::uint64_t z) {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

Rng::Rng(std::uint64_t seed, std::uint64_t stream) {
  std::uint64_t state = mix64(seed) ^ mix64(stream * 0xd1342543de82ef95ull + 1);
  for (auto& s : s_) s = splitmix64(state);
}

namespace {
std::uint64_t rotl(std::uint64_t x, int k) {
  return (x << k) | (x >> (64 - k));
}
}  // namespace

std::uint64_t Rng::next() {
  const std::uint64_t result = rotl(s_[1] * 5, 7) * 9;
  const std::uint64_t t = s_[1] << 17;
  s_[2] ^= s_[0];
  s_[3] ^= s_[1];
  s_[1] ^= s_[2];
  s_[0] ^= s_[3];
  s_[2] ^= t;
  s_[3] = rotl(s_[3], 45);
  return result;
}

double Rng::uniform() {
  return static_cast<double>(next() >> 11) * 0x1.0p-53;
}

double Rng::uniform(double lo, double hi) {
  return lo + (hi - lo) * uniform();
}

int Rng::integer(int lo, int hi) {
  const std::uint64_t span = static_cast<std::uint64_t>(static_cast<long long>(hi) - lo) + 1;
  // Reject the top partial block so every value is equally likely.
  const std::uint64_t limit = UINT64_MAX - UINT64_MAX % span;
  std::uint64_t r = next();
  while (r >= limit) r = next();
  return static_cast<int>(lo + static_cast<long long>(r % span));
}

double hashed_normal(std::uint64_t key, std::uint64_t index) {
  const std::uint64_t a = mix64(key ^ mix64(2 * index + 1));
  const std::uint64_t b = mix64(a ^ 0x6a09e667f3bcc909ull);
  const double u1 = static_cast<double>(a >> 11) * 0x1.0p-53;
  const double u2 = static_cast<double>(b >> 11) * 0x1.0p-53;
  return std::sqrt(-2.0 * std::log(1.0 - u1)) * std::cos(2.0 * M_PI * u2);
}

double Rng::normal() {
  if (have_spare_) {
    have_spare_ = false;
    return spare_;
  }
  // 1 - uniform() lies in (0, 1]: the logarithm is finite.
  const double r = std::sqrt(-2.0 * std::log(1.0 - uniform()));
  const double a = 2.0 * M_PI * uniform();
  spare_ = r * std::sin(a);
  have_spare_ = true;
  return r * std::cos(a);
}

}  // namespace petra::sim
