// 3x3 linear algebra over a scalar type S (double or Fixed<F>), for the
// geometry that must also run in fixed point: an LDL^T factorisation (solve,
// log-determinant and Mahalanobis form without forming det or inverse, whose
// cubic magnitudes would overflow a Q format) and a cyclic Jacobi
// eigen-decomposition of a symmetric matrix (bounded sweeps, no recursion).
// Inputs and outputs are Eigen fixed-size values; no heap, no I/O.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <type_traits>

namespace petra {

// Scalar helpers so templated code reads the same for double and Fixed<F>.
template <class S>
S from_count(std::size_t n) {
  if constexpr (std::is_floating_point_v<S>) {
    return static_cast<S>(n);
  } else {
    return S(static_cast<long>(n));
  }
}
inline double to_double(double v) {
  return v;
}

template <class S>
using Vec2T = Eigen::Matrix<S, 2, 1>;
template <class S>
using Vec3T = Eigen::Matrix<S, 3, 1>;
template <class S>
using Mat3T = Eigen::Matrix<S, 3, 3>;

// A = L D L^T for a symmetric A (lower triangle read). `positive` is true when
// every pivot is > 0, i.e. A is positive definite to working precision.
template <class S>
struct Ldlt3 {
  S l10{}, l20{}, l21{};
  S d0{}, d1{}, d2{};
  bool positive = false;

  // Solves A x = b (valid only when positive).
  Vec3T<S> solve(const Vec3T<S>& b) const {
    const S z0 = b(0);
    const S z1 = b(1) - l10 * z0;
    const S z2 = b(2) - l20 * z0 - l21 * z1;
    const S x2 = z2 / d2;
    const S x1 = z1 / d1 - l21 * x2;
    const S x0 = z0 / d0 - l10 * x1 - l20 * x2;
    return Vec3T<S>(x0, x1, x2);
  }
  // y^T A^-1 y.
  S mahalanobis(const Vec3T<S>& y) const {
    const S z0 = y(0);
    const S z1 = y(1) - l10 * z0;
    const S z2 = y(2) - l20 * z0 - l21 * z1;
    return z0 * z0 / d0 + z1 * z1 / d1 + z2 * z2 / d2;
  }
  // ln |det A| = sum of ln of the pivots (valid only when positive).
  S log_det() const {
    using std::log;
    return log(d0) + log(d1) + log(d2);
  }
};

template <class S>
Ldlt3<S> ldlt3(const Mat3T<S>& a) {
  Ldlt3<S> f;
  const S zero(0);
  f.d0 = a(0, 0);
  if (!(f.d0 > zero)) return f;
  f.l10 = a(1, 0) / f.d0;
  f.l20 = a(2, 0) / f.d0;
  f.d1 = a(1, 1) - f.l10 * a(1, 0);
  if (!(f.d1 > zero)) return f;
  f.l21 = (a(2, 1) - f.l20 * a(1, 0)) / f.d1;
  f.d2 = a(2, 2) - f.l20 * a(2, 0) - f.l21 * f.l21 * f.d1;
  f.positive = f.d2 > zero;
  return f;
}

// Eigenvalues ascending, eigenvectors in the matching columns (orthonormal).
template <class S>
struct SymEigen3 {
  Vec3T<S> values;
  Mat3T<S> vectors;
  int sweeps = 0;
};

// Cyclic Jacobi rotations; stops when the off-diagonal part is negligible
// against the diagonal or after max_sweeps (3x3 converges in 4-6 sweeps).
template <class S>
SymEigen3<S> sym_eigen3(const Mat3T<S>& input, int max_sweeps = 12) {
  using std::abs;
  using std::sqrt;
  Mat3T<S> a = input;
  Mat3T<S> v = Mat3T<S>::Identity();
  const S zero(0), one(1), half(0.5);
  const S big_theta(1e4);  // beyond it t = 1/(2 theta) to first order; avoids theta^2 overflow
  int sweep = 0;
  for (; sweep < max_sweeps; ++sweep) {
    const S off = abs(a(0, 1)) + abs(a(0, 2)) + abs(a(1, 2));
    const S diag = abs(a(0, 0)) + abs(a(1, 1)) + abs(a(2, 2));
    if (off == zero || off <= diag * S(1e-18)) break;
    constexpr int kPairs[3][2] = {{0, 1}, {0, 2}, {1, 2}};
    for (const auto& pq : kPairs) {
      const int p = pq[0], q = pq[1];
      const S apq = a(p, q);
      if (apq == zero) continue;
      const S theta = (a(q, q) - a(p, p)) / (S(2) * apq);
      S t;
      if (abs(theta) > big_theta) {
        t = half / theta;
      } else {
        t = one / (abs(theta) + sqrt(theta * theta + one));
        if (theta < zero) t = -t;
      }
      const S c = one / sqrt(t * t + one);
      const S s = t * c;
      a(p, p) = a(p, p) - t * apq;
      a(q, q) = a(q, q) + t * apq;
      a(p, q) = a(q, p) = zero;
      const int r = 3 - p - q;
      const S arp = a(r, p), arq = a(r, q);
      a(r, p) = a(p, r) = c * arp - s * arq;
      a(r, q) = a(q, r) = s * arp + c * arq;
      for (int k = 0; k < 3; ++k) {
        const S vkp = v(k, p), vkq = v(k, q);
        v(k, p) = c * vkp - s * vkq;
        v(k, q) = s * vkp + c * vkq;
      }
    }
  }
  // Sort ascending (three elements: insertion sort).
  SymEigen3<S> out;
  int order[3] = {0, 1, 2};
  for (int i = 1; i < 3; ++i)
    for (int j = i; j > 0 && a(order[j], order[j]) < a(order[j - 1], order[j - 1]); --j) {
      const int tmp = order[j];
      order[j] = order[j - 1];
      order[j - 1] = tmp;
    }
  for (int i = 0; i < 3; ++i) {
    out.values(i) = a(order[i], order[i]);
    out.vectors.col(i) = v.col(order[i]);
  }
  out.sweeps = sweep;
  return out;
}

}  // namespace petra
