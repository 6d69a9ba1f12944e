// An intersection routine for tests, independent of the renderer's: the
// rock's face polygons are cut into triangles and intersected one by one
// (Moller-Trumbore), the ground is the plane z = 0. The renderer instead
// clips the ray against the rock's half-spaces (Cyrus-Beck); agreeing
// answers from the two are evidence that both are right. Plain arithmetic
// (no Eigen in the loop) keeps it quick in unoptimised test builds.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "sim/scene/scene.hpp"

namespace petra::sim::check {

inline constexpr double kNoHit = std::numeric_limits<double>::infinity();

struct Hit {
  bool rock = false;
  bool ground = false;
  int face = -1;
  double t = kNoHit;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
};

class IndependentCaster {
 public:
  explicit IndependentCaster(const Scene& s) : scene_(s) {
    double sum[3] = {0, 0, 0};
    int n = 0;
    for (std::size_t f = 0; f < s.rock.faces.size(); ++f) {
      const auto& poly = s.rock.faces[f].polygon;
      for (std::size_t k = 1; k + 1 < poly.size(); ++k)
        tris_.push_back({v3(poly[0]), v3(poly[k]), v3(poly[k + 1]), static_cast<int>(f)});
      for (const auto& p : poly) {
        for (int i = 0; i < 3; ++i) sum[i] += p[i];
        ++n;
      }
    }
    centre_ = {sum[0] / n, sum[1] / n, sum[2] / n};
    for (const auto& t : tris_)
      for (const V& p : {t.a, t.b, t.c})
        radius_ = std::max(radius_, std::sqrt(dot(sub(p, centre_), sub(p, centre_))));
    radius_ += 1e-3;
  }

  // First hit of o + t d (t > t_min) among the rock's above-ground surface and the ground.
  Hit first_hit(const Eigen::Vector3d& origin, const Eigen::Vector3d& dir,
                double t_min = 0.0) const {
    const V o = v3(origin), d = v3(dir);
    Hit h;
    if (near_rock(o, d)) {
      for (const auto& tri : tris_) {
        const double t = ray_triangle(o, d, tri, t_min);
        if (t < h.t && o.z + t * d.z >= 0.0) {
          h.t = t;
          h.rock = true;
          h.face = tri.face;
        }
      }
    }
    if (d.z < 0) {
      const double t = -o.z / d.z;
      if (t > t_min && t < h.t) {
        h = Hit{};
        h.ground = true;
        h.t = t;
      }
    }
    if (std::isfinite(h.t)) h.point = origin + h.t * dir;
    return h;
  }

  // Shadow by a ray toward the sun (ground) or the face's orientation (rock).
  bool shadowed(const Hit& h) const {
    if (h.rock)
      return scene_.rock.faces[static_cast<std::size_t>(h.face)].plane.normal.dot(scene_.sun_dir) <=
             0;
    if (!h.ground) return false;
    const V o = v3(h.point), d = v3(scene_.sun_dir);
    if (!near_rock(o, d)) return false;
    for (const auto& tri : tris_)
      if (std::isfinite(ray_triangle(o, d, tri, 1e-9))) return true;
    return false;
  }

 private:
  struct V {
    double x, y, z;
  };
  struct Tri {
    V a, b, c;
    int face;
  };
  static V v3(const Eigen::Vector3d& p) { return {p.x(), p.y(), p.z()}; }
  static V sub(const V& a, const V& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
  static double dot(const V& a, const V& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
  static V cross(const V& a, const V& b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
  }

  bool near_rock(const V& o, const V& d) const {
    const V oc = sub(centre_, o);
    const double along = dot(oc, d);
    return dot(oc, oc) - along * along <= radius_ * radius_;
  }

  static double ray_triangle(const V& o, const V& d, const Tri& tri, double t_min) {
    const V e1 = sub(tri.b, tri.a), e2 = sub(tri.c, tri.a);
    const V p = cross(d, e2);
    const double det = dot(e1, p);
    if (std::abs(det) < 1e-14) return kNoHit;
    const V s = sub(o, tri.a);
    const double u = dot(s, p) / det;
    if (u < 0 || u > 1) return kNoHit;
    const V q = cross(s, e1);
    const double v = dot(d, q) / det;
    if (v < 0 || u + v > 1) return kNoHit;
    const double t = dot(e2, q) / det;
    return t > t_min ? t : kNoHit;
  }

  const Scene& scene_;
  std::vector<Tri> tris_;
  V centre_{0, 0, 0};
  double radius_ = 0;
};

// Points every ~0.5 mm along the edges of the rock's part above the ground.
inline std::vector<Eigen::Vector3d> exposed_edge_points(const ConvexRock& r) {
  std::vector<Eigen::Vector3d> pts;
  for (const auto& f : r.faces) {
    const Polygon3 p = exposed_polygon(f);
    for (std::size_t i = 0; i < p.size(); ++i) {
      const Eigen::Vector3d &a = p[i], &b = p[(i + 1) % p.size()];
      const int n = std::max(1, static_cast<int>((b - a).norm() / 0.5));
      for (int k = 0; k < n; ++k) pts.push_back(a + (b - a) * (double(k) / n));
    }
  }
  return pts;
}

// How deep p lies inside the rock (<= 0 outside).
inline double depth_inside(const ConvexRock& r, const Eigen::Vector3d& p) {
  double worst = -INFINITY;
  for (const auto& f : r.faces) worst = std::max(worst, f.plane.normal.dot(p) - f.plane.offset_mm);
  return -worst;
}

}  // namespace petra::sim::check
