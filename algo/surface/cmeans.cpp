#include "algo/surface/cmeans.hpp"

#include <cmath>

namespace petra {

Status validate(const CMeansParams& p) {
  if (p.max_iterations < 1 || p.max_iterations > 10000)
    return Error::make(Errc::invalid_argument, "c-means: max_iterations %d not in 1..10000",
                       p.max_iterations);
  if (!(p.regularisation > 0.0) || !(p.regularisation < 1.0))
    return Error::make(Errc::invalid_argument, "c-means: regularisation %.3g not in (0, 1)",
                       p.regularisation);
  return {};
}

template Status cmeans_initial_partition<double>(std::span<const Vec3T<double>>, int,
                                                 std::span<std::uint8_t>);
template Result<CMeansResultT<double>> cmeans<double>(std::span<const Vec3T<double>>, int,
                                                      const CMeansParams&, std::span<std::uint8_t>);

}  // namespace petra
