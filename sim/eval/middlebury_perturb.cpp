#include "sim/eval/middlebury_perturb.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

namespace petra::eval {

namespace {

// One standard normal sample per call (Box-Muller on two mt19937 words).
class Normal {
 public:
  explicit Normal(std::uint32_t seed) : gen_(seed) {}
  double next() {
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    const double u1 = (static_cast<double>(gen_()) + 1.0) / 4294967296.0;  // (0, 1]
    const double u2 = static_cast<double>(gen_()) / 4294967296.0;
    const double r = std::sqrt(-2.0 * std::log(u1));
    spare_ = r * std::sin(2.0 * M_PI * u2);
    has_spare_ = true;
    return r * std::cos(2.0 * M_PI * u2);
  }

 private:
  std::mt19937 gen_;
  double spare_ = 0;
  bool has_spare_ = false;
};

}  // namespace

Status validate(const Perturbation& p) {
  if (!(p.gain > 0.0 && p.gain <= 4.0))
    return Error::make(Errc::invalid_argument, "perturbation: gain %g outside (0, 4]", p.gain);
  if (!(std::fabs(p.offset) <= 255.0))
    return Error::make(Errc::invalid_argument, "perturbation: offset %g outside [-255, 255]",
                       p.offset);
  if (!(p.noise_sigma >= 0.0 && p.noise_sigma <= 64.0))
    return Error::make(Errc::invalid_argument, "perturbation: noise sigma %g outside [0, 64]",
                       p.noise_sigma);
  if (!(p.vignetting >= 0.0 && p.vignetting < 1.0))
    return Error::make(Errc::invalid_argument, "perturbation: vignetting %g outside [0, 1)",
                       p.vignetting);
  return {};
}

void perturb(io::GrayImage& image, const Perturbation& p) {
  Normal normal(p.seed);
  const double cx = 0.5 * (image.width - 1), cy = 0.5 * (image.height - 1);
  const double r2max = std::max(1.0, cx * cx + cy * cy);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      std::uint8_t& v = image.pixels[static_cast<std::size_t>(y) * image.width + x];
      const double r2 = ((x - cx) * (x - cx) + (y - cy) * (y - cy)) / r2max;
      double out = (p.gain * v + p.offset) * (1.0 - p.vignetting * r2);
      if (p.noise_sigma > 0.0) out += p.noise_sigma * normal.next();
      v = static_cast<std::uint8_t>(std::clamp(std::lround(out), 0L, 255L));
    }
}

Result<Perturbation> parse_perturbation(const std::string& text) {
  Perturbation p;
  double seed = 1;
  const int n = std::sscanf(text.c_str(), "%lf,%lf,%lf,%lf,%lf", &p.gain, &p.offset, &p.noise_sigma,
                            &seed, &p.vignetting);
  if (n < 3)
    return Error::make(Errc::invalid_argument,
                       "perturbation \"%s\": expected gain,offset,sigma[,seed[,vignetting]]",
                       text.c_str());
  if (!(seed >= 0 && seed <= 4294967295.0 && seed == std::floor(seed)))
    return Error::make(Errc::invalid_argument, "perturbation: seed %g is not a 32-bit count", seed);
  p.seed = static_cast<std::uint32_t>(seed);
  PETRA_TRY(validate(p));
  return p;
}

}  // namespace petra::eval
