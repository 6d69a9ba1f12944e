#include "algo/surface/grind_qualify.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace petra {

namespace {

// Ray grazing the face: a triangle's pixel footprint is bounded by this cos.
constexpr double kMinCos = 0.1;
// The 1-sigma reported when the face's points give none.
constexpr double kUnknownSigmaDeg = 180.0;
constexpr double kUnknownSigmaMm = 1e6;

double angle_between_deg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b)) * 180.0 / M_PI;
}

// Independent measurements a triangle stands for: the pixels it covers,
// its area across the ray (seen) over a pixel's there; without a seen area,
// its own area taken to lie on the face. Unknown rig: a pixel-grid Delaunay
// mesh has two triangles per pixel.
double pixels_of(const FaceSample& s, const Eigen::Vector3d& n, const Eigen::Vector3d& camera,
                 const DepthNoise& noise) {
  if (!noise.known()) return 0.5;
  const Eigen::Vector3d ray = s.p - camera;
  const double r = ray.norm();
  if (!(r > 0)) return 0;
  const double pixel_across = (r / noise.focal_px) * (r / noise.focal_px);
  if (s.seen > 0) return static_cast<double>(s.seen) / pixel_across;
  const double cos = std::max(std::abs(n.dot(ray)) / r, kMinCos);
  return static_cast<double>(s.area) / (pixel_across / cos);
}

// Uncertainty of the plane (n, through c) from the samples `use` accepts.
template <class Use>
Result<PlaneUncertainty> uncertainty(std::span<const FaceSample> patch, const Eigen::Vector3d& n,
                                     const Eigen::Vector3d& c, const Eigen::Vector3d& camera,
                                     const DepthNoise& noise, Use&& use) {
  PlaneInformation info(n, c, camera, noise);
  for (const FaceSample& s : patch)
    if (use(s)) info.add(s.p, pixels_of(s, n, camera, noise));
  return info.finish();
}

PlaneVerdict verdict_of(const GrindPlane& p, const Footprint& f, const GrindParams& params) {
  if (p.view_angle_deg > params.max_view_angle_deg) return PlaneVerdict::faces_away;
  if (!f.covered) return PlaneVerdict::too_small;
  if (f.rms_mm > params.max_footprint_rms_mm) return PlaneVerdict::too_rough;
  if (p.normal_sigma_deg > params.max_normal_sigma_deg ||
      p.offset_sigma_mm > params.max_offset_sigma_mm)
    return PlaneVerdict::too_uncertain;
  return PlaneVerdict::accepted;
}

}  // namespace

Status qualify_plane(std::span<const FaceSample> patch, std::size_t core,
                     const Eigen::Vector3d& camera, const GrindParams& params,
                     const DepthNoise& noise, Arena& arena, GrindPlane& plane,
                     const DiscReach* reach) {
  plane.face_normal = plane.normal;
  plane.face_centroid_mm = plane.centroid_mm;
  const Eigen::Vector3d n = plane.normal;
  const double d = -n.dot(plane.centroid_mm);
  FootprintParams fp;
  fp.diameter_mm = params.grinder_diameter_mm;
  fp.min_coverage = params.min_footprint_coverage;
  fp.max_rms_mm = params.max_footprint_rms_mm;
  fp.reach = reach;
  Footprint f;  // a patch of fewer than 3 triangles holds no disc
  if (patch.size() >= 3) {
    auto found = find_footprint(patch, n, plane.centroid_mm, fp, arena);
    if (!found) return found.error();
    f = *found;
  }
  // Where the grinder touches: the disc's centre on the surface (a curved
  // face stands off its whole-patch plane there by millimetres), or the
  // face's centroid when no disc fits.
  const Eigen::Vector3d at = f.covered ? f.centre_mm : plane.centroid_mm;
  auto face = uncertainty(patch.first(std::min(core, patch.size())), n, at, camera, noise,
                          [](const FaceSample&) { return true; });
  plane.centroid_mm = at;
  plane.footprint_reach = f.reach;
  // Too few or collinear points for a figure: as uncertain as can be.
  plane.normal_sigma_deg = face ? face->normal_sigma_deg : kUnknownSigmaDeg;
  plane.offset_sigma_mm = face ? face->offset_sigma_mm : kUnknownSigmaMm;
  if (f.covered && face) {
    plane.footprint_rms_mm = f.rms_mm;
    plane.footprint_pv_mm = f.peak_to_valley_mm;
    plane.footprint_coverage = f.coverage;
    const double r = params.grinder_diameter_mm / 2.0;
    auto disc = uncertainty(patch, f.normal, f.centre_mm, camera, noise, [&](const FaceSample& s) {
      const Eigen::Vector3d q = s.p - f.centre_mm;
      const double along = q.dot(n);
      return q.squaredNorm() - along * along <= r * r;
    });
    plane.footprint_normal = f.normal;
    if (disc) {
      const double k = params.agree_sigmas;
      const double sn = std::hypot(disc->normal_sigma_deg, face->normal_sigma_deg);
      const double so = std::hypot(disc->offset_sigma_mm, face->offset_sigma_mm);
      plane.footprint_agrees =
          angle_between_deg(f.normal, n) <= k * sn && std::abs(n.dot(f.centre_mm) + d) <= k * so;
      if (!plane.footprint_agrees && params.report_disc_plane) {
        plane.footprint_local = true;
        plane.normal = f.normal;
        plane.centroid_mm = f.centre_mm;
        plane.normal_sigma_deg = disc->normal_sigma_deg;
        plane.offset_sigma_mm = disc->offset_sigma_mm;
      }
    }
  }
  plane.view_angle_deg = angle_between_deg(plane.normal, camera - plane.centroid_mm);
  plane.verdict = verdict_of(plane, f, params);
  return {};
}

}  // namespace petra
