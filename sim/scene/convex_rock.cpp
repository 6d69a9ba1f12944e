#include "sim/scene/convex_rock.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace petra::sim {

namespace {

// A square of half-size `half` on the plane, counter-clockwise around its normal.
Polygon3 plane_square(const HalfSpace& h, const Eigen::Vector3d& around, double half) {
  const Eigen::Vector3d& n = h.normal;
  const Eigen::Vector3d helper =
      std::abs(n.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  const Eigen::Vector3d u = n.cross(helper).normalized();
  const Eigen::Vector3d v = n.cross(u);  // u x v = n
  const Eigen::Vector3d o = around + n * (h.offset_mm - n.dot(around));
  return {o + half * (-u - v), o + half * (u - v), o + half * (u + v), o + half * (-u + v)};
}

// Merges vertices closer than `tol` (several planes through one corner leave
// near-duplicates after clipping).
Polygon3 dedupe(const Polygon3& poly, double tol) {
  Polygon3 out;
  for (const auto& p : poly)
    if (out.empty() || (p - out.back()).norm() > tol) out.push_back(p);
  while (out.size() > 1 && (out.front() - out.back()).norm() <= tol) out.pop_back();
  return out;
}

}  // namespace

Result<ConvexRock> make_convex_rock(const std::vector<HalfSpace>& planes,
                                    const Eigen::Vector3d& around, double extent_mm) {
  ConvexRock rock;
  const double half = 4.0 * extent_mm;
  for (std::size_t i = 0; i < planes.size(); ++i) {
    Polygon3 poly = plane_square(planes[i], around, half);
    for (std::size_t j = 0; j < planes.size() && !poly.empty(); ++j)
      if (j != i) poly = clip_polygon(poly, planes[j].normal, planes[j].offset_mm);
    poly = dedupe(poly, 1e-7);
    if (poly.size() < 3 || polygon_area(poly) < 1e-6) continue;
    rock.faces.push_back({planes[i], poly});
  }
  if (rock.faces.size() < 4)
    return Error::make(Errc::degenerate, "rock: only %zu faces remain", rock.faces.size());
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(INFINITY), hi = -lo;
  for (const auto& f : rock.faces)
    for (const auto& p : f.polygon) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
  if ((hi - lo).maxCoeff() > 2.0 * extent_mm)
    return Error::make(Errc::degenerate, "rock: not bounded within %.0f mm", extent_mm);
  rock.centre = 0.5 * (lo + hi);
  for (const auto& f : rock.faces)
    for (const auto& p : f.polygon)
      rock.radius_mm = std::max(rock.radius_mm, (p - rock.centre).norm());
  rock.radius_mm += 1e-6;
  return rock;
}

void translate_rock(ConvexRock& rock, const Eigen::Vector3d& shift) {
  for (auto& f : rock.faces) {
    f.plane.offset_mm += f.plane.normal.dot(shift);
    for (auto& p : f.polygon) p += shift;
  }
  rock.centre += shift;
}

namespace {

// Quick rejection: does the ray pass within the bounding sphere?
bool near_sphere(const ConvexRock& rock, const Eigen::Vector3d& o, const Eigen::Vector3d& dir) {
  const Eigen::Vector3d oc = rock.centre - o;
  const double along = oc.dot(dir);
  const double r2 = rock.radius_mm * rock.radius_mm;
  const double c2 = oc.squaredNorm();
  if (along < 0 && c2 > r2) return false;
  return c2 - along * along <= r2;
}

}  // namespace

RockEntry ray_enter_rock(const ConvexRock& rock, const Eigen::Vector3d& o,
                         const Eigen::Vector3d& dir, double t_min, double t_max) {
  RockEntry miss;
  if (!near_sphere(rock, o, dir)) return miss;
  // Cyrus-Beck: the ray is inside every half-space on [t_in, t_out].
  double t_in = -INFINITY, t_out = INFINITY;
  int face_in = -1;
  for (std::size_t i = 0; i < rock.faces.size(); ++i) {
    const HalfSpace& h = rock.faces[i].plane;
    const double denom = h.normal.dot(dir);
    const double num = h.offset_mm - h.normal.dot(o);
    if (denom == 0.0) {
      if (num < 0) return miss;
      continue;
    }
    const double t = num / denom;
    if (denom < 0) {
      if (t > t_in) {
        t_in = t;
        face_in = static_cast<int>(i);
      }
    } else if (t < t_out) {
      t_out = t;
    }
    if (t_in > t_out) return miss;
  }
  if (face_in < 0 || t_in < t_min || t_in > t_max) return miss;
  return {face_in, t_in};
}

bool ray_meets_rock(const ConvexRock& rock, const Eigen::Vector3d& o, const Eigen::Vector3d& dir,
                    double t_min) {
  if (!near_sphere(rock, o, dir)) return false;
  double t_in = t_min, t_out = INFINITY;
  for (const auto& f : rock.faces) {
    const HalfSpace& h = f.plane;
    const double denom = h.normal.dot(dir);
    const double num = h.offset_mm - h.normal.dot(o);
    if (denom == 0.0) {
      if (num < 0) return false;
      continue;
    }
    const double t = num / denom;
    if (denom < 0)
      t_in = std::max(t_in, t);
    else
      t_out = std::min(t_out, t);
    if (t_in >= t_out) return false;
  }
  return true;
}

Polygon3 exposed_polygon(const RockFace& face) {
  return clip_polygon(face.polygon, -Eigen::Vector3d::UnitZ(), 0.0);
}

}  // namespace petra::sim
