// A ray-cast test scene: a flat ground (z = 0, world z up) and a convex
// polyhedral rock standing on it, seen by a distortion-free pinhole. Gives
// per-pixel world points with their true surface, for the reconstruction
// tests (no images, no matcher). Header-only; tests may allocate.
#pragma once

#include <Eigen/Geometry>
#include <cmath>
#include <random>
#include <vector>

#include "algo/core/image_view.hpp"
#include "algo/mesh/cloud.hpp"

namespace petra::test {

struct PinholeView {
  double f_px = 800;
  double cx = 512, cy = 384;
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();  // world -> camera
  Eigen::Vector3d T = Eigen::Vector3d::Zero();
  Eigen::Vector3d centre() const { return -(R.transpose() * T); }
  Eigen::Vector2d project(const Eigen::Vector3d& pw) const {
    const Eigen::Vector3d pc = R * pw + T;
    return {f_px * pc.x() / pc.z() + cx, f_px * pc.y() / pc.z() + cy};
  }
};

// A camera at `eye` looking at `target`, image y pointing "down" (towards -z).
inline PinholeView look_at(const Eigen::Vector3d& eye, const Eigen::Vector3d& target,
                           double f_px = 800) {
  PinholeView v;
  v.f_px = f_px;
  const Eigen::Vector3d z = (target - eye).normalized();
  const Eigen::Vector3d x = z.cross(Eigen::Vector3d::UnitZ()).normalized();
  const Eigen::Vector3d y = z.cross(x);
  v.R.row(0) = x.transpose();
  v.R.row(1) = y.transpose();
  v.R.row(2) = z.transpose();
  v.T = -(v.R * eye);
  return v;
}

// Half-space n . p + d <= 0 (n outward, unit).
struct HalfSpace {
  Eigen::Vector3d n;
  double d;
};

// The intersection of the half-spaces and, when sphere_radius_mm > 0, a ball.
struct Rock {
  std::vector<HalfSpace> faces;
  Eigen::Vector3d sphere_centre_mm = Eigen::Vector3d::Zero();
  double sphere_radius_mm = 0;  // its surface index is faces.size()
};

// A ridge rock: a box footprint (+-hx, +-hy), walls up to wall_h, and a roof
// of two facets tilted +-roof_deg about the y axis meeting at the ridge.
inline Rock ridge_rock(double hx = 40, double hy = 30, double ridge_h = 55, double roof_deg = 25) {
  Rock r;
  auto add = [&](Eigen::Vector3d n, const Eigen::Vector3d& point) {
    n.normalize();
    r.faces.push_back({n, -n.dot(point)});
  };
  const double s = std::sin(roof_deg * M_PI / 180), c = std::cos(roof_deg * M_PI / 180);
  add({s, 0, c}, {0, 0, ridge_h});   // roof facet facing +x
  add({-s, 0, c}, {0, 0, ridge_h});  // roof facet facing -x
  add({1, 0, 0}, {hx, 0, 0});
  add({-1, 0, 0}, {-hx, 0, 0});
  add({0, 1, 0}, {0, hy, 0});
  add({0, -1, 0}, {0, -hy, 0});
  add({0, 0, -1}, {0, 0, 0});
  return r;
}

struct Cloud {
  std::vector<Eigen::Vector3d> xyz;
  std::vector<PixelPos> px;
  std::vector<int> surface;  // -1 ground, else the rock face index
};

// Casts one ray per pixel of `roi`; noise_mm moves points along their ray.
inline Cloud render(const PinholeView& view, const Rect& roi, const Rock& rock, double noise_mm = 0,
                    std::uint64_t seed = 1) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, 1.0);
  Cloud out;
  const Eigen::Vector3d o = view.centre();
  for (int v = roi.y; v < roi.y + roi.h; ++v)
    for (int u = roi.x; u < roi.x + roi.w; ++u) {
      const Eigen::Vector3d dir =
          (view.R.transpose() *
           Eigen::Vector3d((u - view.cx) / view.f_px, (v - view.cy) / view.f_px, 1))
              .normalized();
      double t_in = 0, t_out = 1e12;
      int face_in = -1;
      bool hit = true;
      for (std::size_t k = 0; k < rock.faces.size() && hit; ++k) {
        const double num = -(rock.faces[k].n.dot(o) + rock.faces[k].d);
        const double den = rock.faces[k].n.dot(dir);
        if (std::abs(den) < 1e-15) {
          if (num < 0) hit = false;
          continue;
        }
        const double t = num / den;
        if (den < 0) {
          if (t > t_in) {
            t_in = t;
            face_in = static_cast<int>(k);
          }
        } else if (t < t_out) {
          t_out = t;
        }
        if (t_in > t_out) hit = false;
      }
      if (hit && rock.sphere_radius_mm > 0) {
        const Eigen::Vector3d oc = o - rock.sphere_centre_mm;
        const double b = oc.dot(dir);
        const double disc =
            b * b - (oc.squaredNorm() - rock.sphere_radius_mm * rock.sphere_radius_mm);
        if (disc < 0) {
          hit = false;
        } else {
          const double t0 = -b - std::sqrt(disc), t1 = -b + std::sqrt(disc);
          if (t0 > t_in) {
            t_in = t0;
            face_in = static_cast<int>(rock.faces.size());
          }
          if (t1 < t_out) t_out = t1;
          if (t_in > t_out) hit = false;
        }
      }
      double t;
      int surface;
      if (hit && face_in >= 0) {
        t = t_in;
        surface = face_in;
      } else {
        if (!(dir.z() < 0)) continue;
        t = -o.z() / dir.z();
        surface = -1;
      }
      t += noise_mm * noise(rng);
      out.xyz.push_back(o + t * dir);
      out.px.push_back({static_cast<std::int16_t>(u), static_cast<std::int16_t>(v)});
      out.surface.push_back(surface);
    }
  return out;
}

}  // namespace petra::test
