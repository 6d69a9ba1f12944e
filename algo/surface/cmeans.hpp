// C-means clustering exactly as the paper's equations 9-12 (docs/method.md 4a), over
// a scalar type S (double or Fixed<F>), for 3-component samples:
//   eq. 9   initial partition: sum(i) = x_i1 + x_i2 + x_i3, MA/MI its max/min,
//           a_i = (c-1)(sum(i)-MI)/(MA-MI) + 1, x_i -> class round(a_i);
//   eq. 10  per class mean u_j and covariance Sigma_j = 1/n_j sum(x x^T - u u^T)
//           (accumulated about u_j: the same matrix without the cancellation);
//   eq. 11  x goes to the class minimising
//           d(x, w_j) = ln|det Sigma_j| + (x-u_j)^T Sigma_j^-1 (x-u_j) - 2 ln(n_j/N);
//   eq. 12  recompute the centres; stop when no sample changes class.
// Petra adds the guards the paper lacks:
//   - singular covariance: Sigma_j + lambda I with lambda = regularisation x
//     trace(Sigma_all)/3 (a class of coplanar samples, or of one sample);
//   - empty class: it takes the sample farthest (eq. 11) from its own class;
//   - MA == MI (the sums cannot order the samples): the component with the
//     largest range replaces the sum in eq. 9; all samples equal is an error;
//   - at most max_iterations passes (converged = false if they run out).
// Inputs: samples, c (2..kMaxClasses). Output: a class per sample (0..c-1)
// into a caller span, class statistics in the result. No heap, no scratch.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "algo/core/result.hpp"
#include "algo/mesh/linalg3.hpp"
#include "algo/surface/fixed_point.hpp"

namespace petra {

inline constexpr int kMaxClasses = 8;

struct CMeansParams {
  int max_iterations = 100;
  double regularisation = 1e-3;  // lambda as a fraction of the mean total variance (> 0)
};

template <class S>
struct CMeansClassT {
  Vec3T<S> mean = Vec3T<S>::Zero();
  Mat3T<S> covariance = Mat3T<S>::Zero();  // regularised, as used by eq. 11
  std::size_t count = 0;
};

template <class S>
struct CMeansResultT {
  CMeansClassT<S> classes[kMaxClasses];
  int c = 0;
  int iterations = 0;  // assignment passes (eq. 11) run
  bool converged = false;
  std::size_t reseeded = 0;  // empty-class repairs
};

Status validate(const CMeansParams& p);

// Eq. 9 alone (exposed for tests): class 0..c-1 per sample.
template <class S>
Status cmeans_initial_partition(std::span<const Vec3T<S>> x, int c, std::span<std::uint8_t> labels);

template <class S>
Result<CMeansResultT<S>> cmeans(std::span<const Vec3T<S>> x, int c, const CMeansParams& params,
                                std::span<std::uint8_t> labels);

extern template Status cmeans_initial_partition<double>(std::span<const Vec3T<double>>, int,
                                                        std::span<std::uint8_t>);
extern template Result<CMeansResultT<double>> cmeans<double>(std::span<const Vec3T<double>>, int,
                                                             const CMeansParams&,
                                                             std::span<std::uint8_t>);

}  // namespace petra

#include "algo/surface/cmeans_impl.hpp"
