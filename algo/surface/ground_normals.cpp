#include "algo/surface/ground_normals.hpp"

#include <algorithm>
#include <cmath>

namespace petra {

Status validate(const GroundNormalParams& p) {
  if (!(p.max_lean_deg > 0.0 && p.max_lean_deg < 90.0))
    return Error::make(Errc::invalid_argument, "ground normals: max_lean_deg %.3g not in (0, 90)",
                       p.max_lean_deg);
  if (!(p.min_share >= 0.0 && p.min_share <= 1.0))
    return Error::make(Errc::invalid_argument, "ground normals: min_share %.3g not in [0, 1]",
                       p.min_share);
  return ok_status();
}

GroundNormalShare ground_normal_share(std::span<const Eigen::Vector3d> normals,
                                      std::span<const PointClass> labels,
                                      const Eigen::Vector3d& plane_normal,
                                      const GroundNormalParams& params) {
  const double min_cos = std::cos(params.max_lean_deg * 3.14159265358979323846 / 180.0);
  GroundNormalShare out;
  std::size_t along = 0;
  const std::size_t n = std::min(normals.size(), labels.size());
  for (std::size_t i = 0; i < n; ++i) {
    if (labels[i] != PointClass::ground || normals[i].squaredNorm() == 0.0) continue;
    ++out.counted;
    // Normals point towards the cameras, as the plane's does: no sign flip.
    if (normals[i].dot(plane_normal) >= min_cos * normals[i].norm()) ++along;
  }
  if (out.counted > 0) out.share = static_cast<double>(along) / static_cast<double>(out.counted);
  return out;
}

}  // namespace petra
