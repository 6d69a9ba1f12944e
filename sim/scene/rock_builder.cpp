#include "sim/scene/rock_builder.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <vector>

namespace petra::sim {

namespace {

constexpr double kDeg = M_PI / 180.0;

struct ShapeParams {
  double b_ratio_lo, b_ratio_hi;  // second semi-axis / first
  double c_ratio_lo, c_ratio_hi;  // vertical semi-axis / first
  int planes_lo, planes_hi;       // rough planes
  double roughness;               // rough planes cut up to this fraction deeper
};

ShapeParams params(RockShape s) {
  switch (s) {
    case RockShape::blocky:
      return {0.70, 0.95, 0.55, 0.80, 18, 26, 0.10};
    case RockShape::rounded:
      return {0.75, 0.95, 0.60, 0.85, 40, 56, 0.05};
    case RockShape::slab:
      return {0.70, 0.95, 0.38, 0.50, 24, 36, 0.08};
  }
  return {0.7, 0.9, 0.6, 0.8, 20, 30, 0.08};
}

// Unit vector at azimuth `az` (from +x, counter-clockwise) and elevation `el`.
Eigen::Vector3d direction(double az, double el) {
  return {std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el)};
}

// A uniformly random rotation (normalised Gaussian quaternion).
Eigen::Matrix3d random_rotation(Rng& rng) {
  Eigen::Quaterniond q(rng.normal(), rng.normal(), rng.normal(), rng.normal());
  q.normalize();
  return q.toRotationMatrix();
}

}  // namespace

Result<BuiltRock> build_rock(Rng& rng, const RockSpec& spec) {
  const ShapeParams sp = params(spec.shape);
  const double a = 0.5 * spec.size_mm;
  const double b = a * rng.uniform(sp.b_ratio_lo, sp.b_ratio_hi);
  const double c = a * rng.uniform(sp.c_ratio_lo, sp.c_ratio_hi);
  // Ellipsoid orientation: any yaw, a little tilt.
  const Eigen::Matrix3d q =
      Eigen::Matrix3d(Eigen::AngleAxisd(rng.uniform(0, 2 * M_PI), Eigen::Vector3d::UnitZ()) *
                      Eigen::AngleAxisd(rng.uniform(-10, 10) * kDeg, Eigen::Vector3d::UnitX()));
  const Eigen::Matrix3d shape_m =
      q * Eigen::Vector3d(a * a, b * b, c * c).asDiagonal() * q.transpose();
  // Support function of the ellipsoid: the plane with normal n touching it.
  auto support = [&](const Eigen::Vector3d& n) { return std::sqrt(n.dot(shape_m * n)); };

  std::vector<HalfSpace> planes;
  // Rough faces: a jittered Fibonacci sphere of directions, randomly rotated.
  const int n_rough = rng.integer(sp.planes_lo, sp.planes_hi);
  const Eigen::Matrix3d spin = random_rotation(rng);
  for (int i = 0; i < n_rough; ++i) {
    const double z = 1.0 - (2.0 * i + 1.0) / n_rough;
    const double phi = i * M_PI * (3.0 - std::sqrt(5.0));
    const double r = std::sqrt(1.0 - z * z);
    Eigen::Vector3d n(r * std::cos(phi), r * std::sin(phi), z);
    n = spin * n + Eigen::Vector3d(rng.uniform(-0.12, 0.12), rng.uniform(-0.12, 0.12),
                                   rng.uniform(-0.12, 0.12));
    n.normalize();
    planes.push_back({n, support(n) * (1.0 - rng.uniform(0.0, sp.roughness)), false});
  }
  // Flat faces toward the cameras, cut deep so they are the largest facets.
  const Eigen::Vector3d& v = spec.toward_cameras;
  const double view_az = std::atan2(v.y(), v.x());
  const double side = rng.coin() ? 1.0 : -1.0;
  // A slab is flat and wide: its faces toward the cameras are tilted further up.
  const bool slab = spec.shape == RockShape::slab;
  std::vector<Eigen::Vector3d> flat;
  if (spec.flat_faces == 2) {
    const double el_lo = slab ? 35 : 22, el_hi = slab ? 60 : 50;
    flat.push_back(
        direction(view_az + side * rng.uniform(18, 40) * kDeg, rng.uniform(el_lo, el_hi) * kDeg));
    flat.push_back(
        direction(view_az - side * rng.uniform(18, 40) * kDeg, rng.uniform(el_lo, el_hi) * kDeg));
  } else {
    const double top_lo = slab ? 68 : 55, top_hi = slab ? 82 : 72;
    const double side_lo = slab ? 22 : 8, side_hi = slab ? 40 : 30;
    flat.push_back(
        direction(view_az + rng.uniform(-20, 20) * kDeg, rng.uniform(top_lo, top_hi) * kDeg));
    flat.push_back(direction(view_az + side * rng.uniform(38, 58) * kDeg,
                             rng.uniform(side_lo, side_hi) * kDeg));
    flat.push_back(direction(view_az - side * rng.uniform(38, 58) * kDeg,
                             rng.uniform(side_lo, side_hi) * kDeg));
  }
  const double cut_lo = spec.flat_faces == 2 ? 0.22 : 0.18;
  const double cut_hi = spec.flat_faces == 2 ? 0.36 : 0.30;
  for (const auto& n : flat)
    planes.push_back({n, support(n) * (1.0 - rng.uniform(cut_lo, cut_hi)), true});

  auto rock = make_convex_rock(planes, Eigen::Vector3d::Zero(), 2.0 * a);
  if (!rock) return rock.error();
  // Tangent planes enclose more than the ellipsoid: scale about its centre so
  // the largest dimension (between the two farthest vertices) is the size asked for.
  double diameter = 0;
  for (const auto& f : rock->faces)
    for (const auto& pa : f.polygon)
      for (const auto& g : rock->faces)
        for (const auto& pb : g.polygon) diameter = std::max(diameter, (pa - pb).norm());
  const double k = spec.size_mm / diameter;
  for (auto& f : rock->faces) {
    f.plane.offset_mm *= k;
    for (auto& p : f.polygon) p *= k;
  }
  rock->centre *= k;
  rock->radius_mm *= k;
  // Sink: the ground cuts the rock 15..35 % of its height above its bottom.
  double zmin = INFINITY, zmax = -INFINITY;
  for (const auto& f : rock->faces)
    for (const auto& p : f.polygon) {
      zmin = std::min(zmin, p.z());
      zmax = std::max(zmax, p.z());
    }
  const double drawn = rng.uniform(0.15, 0.35);  // drawn even when given: keeps the stream
  const double sink = spec.burial.value_or(drawn);
  BuiltRock out;
  out.centre_height_mm = -(zmin + sink * (zmax - zmin));
  out.rock = std::move(*rock);
  translate_rock(out.rock, Eigen::Vector3d(0, 0, out.centre_height_mm));
  return out;
}

}  // namespace petra::sim
