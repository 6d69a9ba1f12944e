#include "sim/scene/face_relief.hpp"

#include <algorithm>
#include <cmath>

#include "sim/scene/rng.hpp"

namespace petra::sim {

namespace {

constexpr int kOctaves = 4;  // wavelengths 20 .. 2.5 mm
constexpr double kLargestMm = 20, kPersistence = 0.6;
constexpr std::uint64_t kStreamFaces = 22;
constexpr int kCalibrationSamples = 20000;

double fractal(const Permutation& perm, const Eigen::Vector3d& x) {
  double sum = 0, amp = 1, lambda = kLargestMm;
  for (int k = 0; k < kOctaves; ++k) {
    sum += amp * gradient_noise(x / lambda + Eigen::Vector3d(13.1 * k, 5.3 * k, 29.7 * k), perm);
    amp *= kPersistence;
    lambda *= 0.5;
  }
  return sum;
}

// Cyrus-Beck: the ray is inside every half-space on [t_in, t_out].
bool clip_to_rock(const ConvexRock& rock, const Eigen::Vector3d& o, const Eigen::Vector3d& dir,
                  double& t_in, double& t_out) {
  const Eigen::Vector3d oc = rock.centre - o;
  const double along = oc.dot(dir), r2 = rock.radius_mm * rock.radius_mm;
  if ((along < 0 && oc.squaredNorm() > r2) || oc.squaredNorm() - along * along > r2) return false;
  t_in = -INFINITY;
  t_out = INFINITY;
  for (const auto& f : rock.faces) {
    const double denom = f.plane.normal.dot(dir);
    const double num = f.plane.offset_mm - f.plane.normal.dot(o);
    if (denom == 0.0) {
      if (num < 0) return false;
      continue;
    }
    const double t = num / denom;
    if (denom < 0)
      t_in = std::max(t_in, t);
    else
      t_out = std::min(t_out, t);
    if (t_in > t_out) return false;
  }
  return true;
}

// s_i(x) given the rock's roughness at x (`rough`: the unscaled fractal,
// the same for every face, so a field point evaluates it once).
double depth_given_rough(const FaceRelief& r, int face, const HalfSpace& plane,
                         const Eigen::Vector3d& x, double rough) {
  const Eigen::Vector3d off = x - r.bulge_centre[static_cast<std::size_t>(face)];
  const Eigen::Vector3d in_plane = off - plane.normal * plane.normal.dot(off);
  double depth = 0.5 * r.curvature_per_mm * in_plane.squaredNorm();
  if (r.rough_scale > 0) depth += std::max(0.0, r.rough_floor + r.rough_scale * rough);
  return depth;
}

// max_i (n_i.x - d_i + s_i(x)) over the faces that can reach x; <= 0 inside.
double rough_field(const ConvexRock& rock, const FaceRelief& r, const Eigen::Vector3d& x,
                   int& face) {
  double best = -INFINITY;
  face = -1;
  double rough = 0;
  bool rough_known = r.rough_scale <= 0;
  for (std::size_t i = 0; i < rock.faces.size(); ++i) {
    const HalfSpace& h = rock.faces[i].plane;
    const double plane = h.normal.dot(x) - h.offset_mm;
    if (plane + r.max_depth_mm < best) continue;  // cannot beat the best
    if (!rough_known) {
      rough = fractal(r.perm, x);
      rough_known = true;
    }
    const double v = plane + depth_given_rough(r, static_cast<int>(i), h, x, rough);
    if (v > best) {
      best = v;
      face = static_cast<int>(i);
    }
  }
  return best;
}

}  // namespace

FractalStats fractal_stats(std::uint64_t seed) {
  Rng rng(seed, kStreamFaces);
  FractalStats st;
  st.perm = make_permutation(rng.next());
  double sum2 = 0;
  const double h = 0.01;
  for (int k = 0; k < kCalibrationSamples; ++k) {
    const Eigen::Vector3d x(rng.uniform(-500, 500), rng.uniform(-500, 500), rng.uniform(-500, 500));
    const double v = fractal(st.perm, x);
    sum2 += v * v;
    st.v_max = std::max(st.v_max, std::abs(v));
    const Eigen::Vector3d g(fractal(st.perm, x + Eigen::Vector3d(h, 0, 0)) - v,
                            fractal(st.perm, x + Eigen::Vector3d(0, h, 0)) - v,
                            fractal(st.perm, x + Eigen::Vector3d(0, 0, h)) - v);
    st.grad_max = std::max(st.grad_max, g.norm() / h);
  }
  st.rms = std::sqrt(sum2 / kCalibrationSamples);
  return st;
}

FaceRelief make_face_relief(const World& world, const FractalStats& st, const ConvexRock& rock) {
  FaceRelief r;
  r.active = world.face_roughness_mm > 0 || world.face_curvature_per_m > 0;
  if (!r.active) return r;
  r.perm = st.perm;
  r.curvature_per_mm = world.face_curvature_per_m / 1000.0;
  for (const auto& f : rock.faces) {
    const Polygon3 exposed = exposed_polygon(f);
    r.bulge_centre.push_back(exposed.size() >= 3 ? polygon_centroid(exposed)
                                                 : polygon_centroid(f.polygon));
  }
  double grad_max = 0;
  if (world.face_roughness_mm > 0) {
    r.rough_scale = world.face_roughness_mm / st.rms;
    r.rough_floor = 1.2 * st.v_max * r.rough_scale;
    grad_max = st.grad_max;
  }
  const double reach = 2 * rock.radius_mm;  // farthest a face point lies from its centre
  r.max_depth_mm = 2 * r.rough_floor + 0.5 * r.curvature_per_mm * reach * reach;
  r.lipschitz = 1.5 * grad_max * r.rough_scale + r.curvature_per_mm * reach;
  return r;
}

FaceRelief make_face_relief(const World& world, std::uint64_t seed, const ConvexRock& rock) {
  const bool active = world.face_roughness_mm > 0 || world.face_curvature_per_m > 0;
  if (!active) return {};
  FractalStats st;
  if (world.face_roughness_mm > 0) {
    st = fractal_stats(seed);
  } else {
    Rng rng(seed, kStreamFaces);
    st.perm = make_permutation(rng.next());
  }
  return make_face_relief(world, st, rock);
}

double face_depth(const FaceRelief& r, int face, const HalfSpace& plane, const Eigen::Vector3d& x) {
  return depth_given_rough(r, face, plane, x, r.rough_scale > 0 ? fractal(r.perm, x) : 0.0);
}

RockEntry ray_enter_rough_rock(const ConvexRock& rock, const FaceRelief& r,
                               const Eigen::Vector3d& o, const Eigen::Vector3d& dir, double t_min,
                               double t_max) {
  RockEntry miss;
  double t_in = 0, t_out = 0;
  if (!clip_to_rock(rock, o, dir, t_in, t_out)) return miss;
  double t = std::max(t_in, t_min);
  const double t_end = std::min(t_out, t_max);
  // Sphere tracing: the field's slope along any direction is at most 1 + L.
  for (int it = 0; it < 300 && t <= t_end; ++it) {
    int face = -1;
    const double g = rough_field(rock, r, o + t * dir, face);
    if (g < 1e-4) return {face, t};
    t += g / (1.0 + r.lipschitz);
  }
  return miss;
}

Eigen::Vector3d rough_face_normal(const ConvexRock& rock, const FaceRelief& r, int face,
                                  const Eigen::Vector3d& x) {
  const HalfSpace& h = rock.faces[static_cast<std::size_t>(face)].plane;
  const double e = 0.02;
  Eigen::Vector3d g;
  for (int k = 0; k < 3; ++k) {
    Eigen::Vector3d d = Eigen::Vector3d::Zero();
    d[k] = e;
    g[k] = (face_depth(r, face, h, x + d) - face_depth(r, face, h, x - d)) / (2 * e);
  }
  // Outward normal of n.x - d + s(x) = 0.
  return (h.normal + g).normalized();
}

}  // namespace petra::sim
