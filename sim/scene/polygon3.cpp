#include "sim/scene/polygon3.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace petra::sim {

Polygon3 clip_polygon(const Polygon3& poly, const Eigen::Vector3d& n, double d) {
  Polygon3 out;
  const std::size_t k = poly.size();
  out.reserve(k + 1);
  for (std::size_t i = 0; i < k; ++i) {
    const Eigen::Vector3d& a = poly[i];
    const Eigen::Vector3d& b = poly[(i + 1) % k];
    const double da = n.dot(a) - d;
    const double db = n.dot(b) - d;
    if (da <= 0) out.push_back(a);
    // An edge crossing the plane contributes its crossing point.
    if ((da < 0 && db > 0) || (da > 0 && db < 0)) out.push_back(a + (b - a) * (da / (da - db)));
  }
  return out;
}

Eigen::Vector3d polygon_vector_area(const Polygon3& poly) {
  Eigen::Vector3d s = Eigen::Vector3d::Zero();
  if (poly.size() < 3) return s;
  const Eigen::Vector3d& o = poly[0];
  for (std::size_t i = 1; i + 1 < poly.size(); ++i) s += (poly[i] - o).cross(poly[i + 1] - o);
  return 0.5 * s;
}

double polygon_area(const Polygon3& poly) {
  return polygon_vector_area(poly).norm();
}

Eigen::Vector3d polygon_centroid(const Polygon3& poly) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  if (poly.empty()) return mean;
  for (const auto& p : poly) mean += p;
  mean /= static_cast<double>(poly.size());
  if (poly.size() < 3) return mean;
  // Fan of triangles from vertex 0, each weighted by its signed area along
  // the polygon's normal.
  const Eigen::Vector3d n = polygon_vector_area(poly);
  const double nn = n.norm();
  if (nn <= 0) return mean;
  const Eigen::Vector3d u = n / nn;
  Eigen::Vector3d acc = Eigen::Vector3d::Zero();
  double total = 0;
  const Eigen::Vector3d& o = poly[0];
  for (std::size_t i = 1; i + 1 < poly.size(); ++i) {
    const double a = 0.5 * u.dot((poly[i] - o).cross(poly[i + 1] - o));
    acc += a * (o + poly[i] + poly[i + 1]) / 3.0;
    total += a;
  }
  return total != 0 ? Eigen::Vector3d(acc / total) : mean;
}

namespace {

double point_segment_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                              const Eigen::Vector3d& b) {
  const Eigen::Vector3d ab = b - a;
  const double l2 = ab.squaredNorm();
  const double t = l2 > 0 ? std::clamp((p - a).dot(ab) / l2, 0.0, 1.0) : 0.0;
  return (a + t * ab - p).norm();
}

}  // namespace

double in_plane_distance_to_polygon(const Polygon3& poly, const Eigen::Vector3d& normal,
                                    const Eigen::Vector3d& p) {
  if (poly.empty()) return INFINITY;
  const Eigen::Vector3d q = p - normal * normal.dot(p - poly[0]);  // projection onto the plane
  if (poly.size() < 3) {
    double best = INFINITY;
    for (std::size_t i = 0; i < poly.size(); ++i)
      best = std::min(best, point_segment_distance(q, poly[i], poly[(i + 1) % poly.size()]));
    return best;
  }
  // Inside a convex polygon: on the same side of every edge. The polygon's
  // own orientation decides which side is "inside".
  const Eigen::Vector3d axis = polygon_vector_area(poly);
  bool inside = true;
  double best = INFINITY;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const Eigen::Vector3d& a = poly[i];
    const Eigen::Vector3d& b = poly[(i + 1) % poly.size()];
    if (axis.dot((b - a).cross(q - a)) < 0) inside = false;
    best = std::min(best, point_segment_distance(q, a, b));
  }
  return inside ? 0.0 : best;
}

double distance_to_polygon(const Polygon3& poly, const Eigen::Vector3d& normal,
                           const Eigen::Vector3d& p) {
  if (poly.empty()) return INFINITY;
  const double h = normal.dot(p - poly[0]);
  const double r = in_plane_distance_to_polygon(poly, normal, p);
  return std::sqrt(h * h + r * r);
}

std::vector<Eigen::Vector3d> polygon_samples(const Polygon3& poly, double step_mm) {
  std::vector<Eigen::Vector3d> pts;
  for (std::size_t i = 1; i + 1 < poly.size(); ++i) {
    const Eigen::Vector3d &a = poly[0], &b = poly[i], &c = poly[i + 1];
    const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
    const int n = std::max(1, static_cast<int>(std::ceil(longest / step_mm)));
    for (int p = 0; p <= n; ++p)
      for (int q = 0; p + q <= n; ++q)
        pts.push_back(a + (b - a) * (double(p) / n) + (c - a) * (double(q) / n));
  }
  return pts;
}

}  // namespace petra::sim
