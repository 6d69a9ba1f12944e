// Total-least-squares plane fit over a scalar type S (double or Fixed<F>):
// the plane A X + B Y + C Z + D = 0 with |(A, B, C)| = 1 minimising the sum
// of squared orthogonal distances (docs/method.md 2a eq. 1, normalised form).
// Centroid and bounding box first, then the covariance of the centred points
// divided by a scale (half the largest extent), so sums stay O(count)
// whatever the units: that keeps a Q format from overflowing and costs
// double nothing.
// Inputs: points (mm) and a selector `use(i) -> bool` or weights `weight(i) >= 0`;
// no heap, two passes.
#pragma once

#include <cstddef>
#include <span>

#include "algo/core/result.hpp"
#include "algo/mesh/linalg3.hpp"

namespace petra {

// n . x + d = 0, |n| = 1; distances are n . x + d (signed, mm).
template <class S>
struct PlaneT {
  Vec3T<S> normal = Vec3T<S>::UnitZ();
  S d{};
  S distance(const Vec3T<S>& p) const { return normal.dot(p) + d; }
};

template <class S>
struct PlaneFitT {
  PlaneT<S> plane;
  Vec3T<S> centroid = Vec3T<S>::Zero();
  S rms{};                 // RMS orthogonal distance of the used points, mm
  S middle_eigen_ratio{};  // lambda_mid / lambda_max: ~0 when the points are collinear
  std::size_t count = 0;
};

// Minimum ratio lambda_mid / lambda_max below which the points are taken as
// collinear (their plane is undefined).
inline constexpr double kCollinearEigenRatio = 1e-6;

namespace plane_fit_detail {

// The weighted centroid of the used points (weight > 0) and the scale the
// moments are divided by (half the largest extent of their bounding box).
template <class S>
struct Spread {
  Vec3T<S> centroid;
  S scale{};
  S weight{};  // total weight
  std::size_t count = 0;
};

template <class S, class Get, class Weight>
Result<Spread<S>> weighted_spread(std::size_t count_all, Get& point, Weight& weight) {
  Spread<S> out;
  Vec3T<S> sum = Vec3T<S>::Zero();
  Vec3T<S> lo = Vec3T<S>::Zero(), hi = Vec3T<S>::Zero();
  std::size_t n = 0;
  for (std::size_t i = 0; i < count_all; ++i) {
    const S w = weight(i);
    if (!(w > S(0))) continue;
    const Vec3T<S>& p = point(i);
    if (n == 0) lo = hi = p;
    for (int k = 0; k < 3; ++k) {
      lo(k) = p(k) < lo(k) ? p(k) : lo(k);
      hi(k) = p(k) > hi(k) ? p(k) : hi(k);
    }
    sum += w * p;
    out.weight += w;
    ++n;
  }
  if (n < 3) return Error::make(Errc::degenerate, "plane fit: %zu points, need at least 3", n);
  out.centroid = sum / out.weight;
  const Vec3T<S> extent = hi - lo;
  S scale = extent(0) > extent(1) ? extent(0) : extent(1);
  out.scale = (extent(2) > scale ? extent(2) : scale) / S(2);
  if (!(out.scale > S(0)))
    return Error::make(Errc::degenerate, "plane fit: all %zu points coincide", n);
  out.count = n;
  return out;
}

}  // namespace plane_fit_detail

// Weighted total least squares: point(k) counts with weight(k) >= 0 (0:
// unused). The plane through the weighted centroid along the smallest
// eigenvector of the weighted scatter; rms is the weighted RMS distance.
template <class S, class Get, class Weight>
Result<PlaneFitT<S>> fit_plane_wtls_by(std::size_t count_all, Get&& point, Weight&& weight) {
  using std::sqrt;
  const auto spread = plane_fit_detail::weighted_spread<S>(count_all, point, weight);
  if (!spread) return spread.error();
  const Vec3T<S> c = spread->centroid;
  const S inv_scale = S(1) / spread->scale;
  Mat3T<S> cov = Mat3T<S>::Zero();
  for (std::size_t i = 0; i < count_all; ++i) {
    const S w = weight(i);
    if (!(w > S(0))) continue;
    const Vec3T<S> q = (point(i) - c) * inv_scale;
    cov(0, 0) += w * q(0) * q(0);
    cov(1, 0) += w * q(1) * q(0);
    cov(2, 0) += w * q(2) * q(0);
    cov(1, 1) += w * q(1) * q(1);
    cov(2, 1) += w * q(2) * q(1);
    cov(2, 2) += w * q(2) * q(2);
  }
  cov(0, 1) = cov(1, 0);
  cov(0, 2) = cov(2, 0);
  cov(1, 2) = cov(2, 1);
  PlaneFitT<S> fit;
  const SymEigen3<S> eig = sym_eigen3<S>(cov);
  const S lmax = eig.values(2);
  fit.middle_eigen_ratio = lmax > S(0) ? eig.values(1) / lmax : S(0);
  if (!(fit.middle_eigen_ratio > S(kCollinearEigenRatio)))
    return Error::make(Errc::degenerate, "plane fit: %zu points are collinear", spread->count);
  Vec3T<S> normal = eig.vectors.col(0);
  normal /= sqrt(normal.squaredNorm());
  fit.plane.normal = normal;
  fit.plane.d = -normal.dot(c);
  fit.centroid = c;
  const S lmin = eig.values(0) > S(0) ? eig.values(0) : S(0);
  fit.rms = spread->scale * sqrt(lmin / spread->weight);
  fit.count = spread->count;
  return fit;
}

// Points given by an accessor: point(k) for k < count, used when use(k).
// The weighted fit with weights 0 and 1 (exact in every scalar type).
template <class S, class Get, class Use>
Result<PlaneFitT<S>> fit_plane_tls_by(std::size_t count_all, Get&& point, Use&& use) {
  return fit_plane_wtls_by<S>(count_all, point,
                              [&](std::size_t i) { return use(i) ? S(1) : S(0); });
}

// Weighted least squares along a direction: the plane minimising the
// squared offsets of the points along `dir` (unit), not across the plane.
// Stereo measures depth along the viewing ray (disparity) and the pixel
// position almost exactly, so for a face seen obliquely this is the error
// model; total least squares also counts the in-plane share of the depth
// error and tilts the normal away from the ray. In a frame (e1, e2, dir):
// dir-offset = a x + b y, normal along dir - a e1 - b e2.
template <class S, class Get, class Weight>
Result<PlaneFitT<S>> fit_plane_along_by(std::size_t count_all, Get&& point, Weight&& weight,
                                        const Vec3T<S>& dir) {
  using std::abs;
  using std::sqrt;
  // Centred coordinates over half the largest extent and moments over the
  // total weight: every term stays O(1), so a Q format cannot overflow.
  const auto spread = plane_fit_detail::weighted_spread<S>(count_all, point, weight);
  if (!spread) return spread.error();
  const Vec3T<S> c = spread->centroid;
  const S scale = spread->scale, wsum = spread->weight;
  const std::size_t n = spread->count;
  const S inv_scale = S(1) / scale;
  PlaneFitT<S> fit;
  // Any unit vector not along dir gives the in-plane basis.
  const Vec3T<S> helper =
      abs(dir(2)) < S(0.9) ? Vec3T<S>(S(0), S(0), S(1)) : Vec3T<S>(S(1), S(0), S(0));
  Vec3T<S> e1 = helper.cross(dir);
  e1 /= sqrt(e1.squaredNorm());
  const Vec3T<S> e2 = dir.cross(e1);
  S sxx{}, sxy{}, syy{}, sxz{}, syz{};
  for (std::size_t i = 0; i < count_all; ++i) {
    const S w = weight(i);
    if (!(w > S(0))) continue;
    const Vec3T<S> q = (point(i) - c) * inv_scale;
    const S x = q.dot(e1), y = q.dot(e2), z = q.dot(dir);
    sxx += w * x * x;
    sxy += w * x * y;
    syy += w * y * y;
    sxz += w * x * z;
    syz += w * y * z;
  }
  sxx /= wsum;
  sxy /= wsum;
  syy /= wsum;
  sxz /= wsum;
  syz /= wsum;
  const S det = sxx * syy - sxy * sxy;
  // The points' footprint across dir must span two directions.
  if (!(det > S(kCollinearEigenRatio) * (sxx + syy) * (sxx + syy)))
    return Error::make(Errc::degenerate, "plane fit: %zu points are collinear across the ray", n);
  const S a = (sxz * syy - syz * sxy) / det;
  const S b = (syz * sxx - sxz * sxy) / det;
  Vec3T<S> normal = dir - a * e1 - b * e2;
  normal /= sqrt(normal.squaredNorm());
  fit.plane.normal = normal;
  fit.plane.d = -normal.dot(c);
  fit.centroid = c;
  S ss{};
  for (std::size_t i = 0; i < count_all; ++i) {
    const S w = weight(i);
    if (!(w > S(0))) continue;
    const S r = normal.dot((point(i) - c) * inv_scale);
    ss += w * r * r;
  }
  fit.rms = scale * sqrt(ss / wsum);
  fit.middle_eigen_ratio = S(1);
  fit.count = n;
  return fit;
}

template <class S, class Use>
Result<PlaneFitT<S>> fit_plane_tls(std::span<const Vec3T<S>> points, Use&& use) {
  return fit_plane_tls_by<S>(
      points.size(), [&](std::size_t i) -> const Vec3T<S>& { return points[i]; }, use);
}

template <class S>
Result<PlaneFitT<S>> fit_plane_tls(std::span<const Vec3T<S>> points) {
  return fit_plane_tls<S>(points, [](std::size_t) { return true; });
}

}  // namespace petra
