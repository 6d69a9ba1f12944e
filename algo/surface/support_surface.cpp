#include "algo/surface/support_surface.hpp"

#include <cmath>

namespace petra {

namespace {

// Height in front of the plane and whether the point lies within the radius along it.
struct Placed {
  double height_mm;
  bool near;
};

Placed place(const Eigen::Vector3d& x, const SupportPlane& plane, double radius_mm) {
  const Eigen::Vector3d rel = x - plane.centroid_mm;
  const double h = plane.normal.dot(rel);
  return {h, (rel - h * plane.normal).squaredNorm() < radius_mm * radius_mm};
}

double plane_radius_mm(const SupportPlane& plane) {
  return std::sqrt(plane.area_mm2 / M_PI);
}

double radius_mm(const SupportPlane& plane, const SupportParams& params) {
  return params.radius_factor * plane_radius_mm(plane);
}

}  // namespace

Status validate(const SupportParams& p) {
  if (!(p.radius_factor > 0.0))
    return Error::make(Errc::invalid_argument, "support: radius_factor %g not > 0",
                       p.radius_factor);
  if (!(p.margin_rms > 0.0))
    return Error::make(Errc::invalid_argument, "support: margin_rms %g not > 0", p.margin_rms);
  if (!(p.click_radii > 0.0))
    return Error::make(Errc::invalid_argument, "support: click_radii %g not > 0", p.click_radii);
  if (!(p.max_share > 0.0 && p.max_share < 1.0))
    return Error::make(Errc::invalid_argument, "support: max_share %g not in (0, 1)", p.max_share);
  return {};
}

RockInFront rock_in_front(std::span<const Eigen::Vector3d> xyz, std::span<const PointClass> labels,
                          std::size_t click, const SupportPlane& plane,
                          const SupportParams& params) {
  const double r = radius_mm(plane, params), margin = params.margin_rms * plane.rms_mm;
  RockInFront out;
  out.plane_radius_mm = plane_radius_mm(plane);
  if (click < xyz.size()) out.click_height_mm = plane.normal.dot(xyz[click] - plane.centroid_mm);
  for (std::size_t i = 0; i < xyz.size() && i < labels.size(); ++i) {
    if (labels[i] != PointClass::rock) continue;
    const Placed p = place(xyz[i], plane, r);
    if (!p.near) continue;
    ++out.near;
    out.in_front += p.height_mm > margin ? 1 : 0;
  }
  return out;
}

bool stands_on(const RockInFront& r, const SupportParams& params) {
  return r.share() > params.max_share && r.click_height_mm > params.click_radii * r.plane_radius_mm;
}

std::size_t drop_support(std::span<const Eigen::Vector3d> xyz, std::span<PointClass> labels,
                         const SupportPlane& plane, const SupportParams& params) {
  const double r = radius_mm(plane, params), margin = params.margin_rms * plane.rms_mm;
  std::size_t dropped = 0;
  for (std::size_t i = 0; i < xyz.size() && i < labels.size(); ++i) {
    if (labels[i] != PointClass::rock) continue;
    const Placed p = place(xyz[i], plane, r);
    if (!p.near || p.height_mm > margin) continue;
    labels[i] = PointClass::ground;
    ++dropped;
  }
  return dropped;
}

}  // namespace petra
