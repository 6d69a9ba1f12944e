// Template body of C-means (algo/surface/cmeans.hpp). Included by that header only;
// double is instantiated once in cmeans.cpp.
#pragma once

#include <cmath>

namespace petra {

namespace cmeans_detail {

inline Status check_sizes(std::size_t n, std::size_t labels, int c) {
  if (c < 2 || c > kMaxClasses)
    return Error::make(Errc::out_of_range, "c-means: c = %d classes, must be 2..%d", c,
                       kMaxClasses);
  if (labels != n)
    return Error::make(Errc::invalid_argument, "c-means: %zu samples but %zu labels", n, labels);
  if (n < static_cast<std::size_t>(c))
    return Error::make(Errc::degenerate, "c-means: %zu samples for c = %d classes", n, c);
  return {};
}

// Per-class mean and covariance about the mean (two passes).
template <class S>
void class_statistics(std::span<const Vec3T<S>> x, std::span<const std::uint8_t> labels, int c,
                      CMeansClassT<S>* cls) {
  Vec3T<S> sum[kMaxClasses];
  for (int j = 0; j < c; ++j) {
    sum[j] = Vec3T<S>::Zero();
    cls[j].count = 0;
    cls[j].covariance = Mat3T<S>::Zero();
  }
  for (std::size_t i = 0; i < x.size(); ++i) {
    sum[labels[i]] += x[i];
    ++cls[labels[i]].count;
  }
  for (int j = 0; j < c; ++j)
    cls[j].mean =
        cls[j].count > 0 ? Vec3T<S>(sum[j] / from_count<S>(cls[j].count)) : Vec3T<S>::Zero();
  for (std::size_t i = 0; i < x.size(); ++i) {
    CMeansClassT<S>& k = cls[labels[i]];
    const Vec3T<S> q = x[i] - k.mean;
    // Lower triangle only; divided by n below.
    k.covariance(0, 0) += q(0) * q(0);
    k.covariance(1, 0) += q(1) * q(0);
    k.covariance(2, 0) += q(2) * q(0);
    k.covariance(1, 1) += q(1) * q(1);
    k.covariance(2, 1) += q(2) * q(1);
    k.covariance(2, 2) += q(2) * q(2);
  }
  for (int j = 0; j < c; ++j) {
    Mat3T<S>& m = cls[j].covariance;
    if (cls[j].count > 0) m /= from_count<S>(cls[j].count);
    m(0, 1) = m(1, 0);
    m(0, 2) = m(2, 0);
    m(1, 2) = m(2, 1);
  }
}

}  // namespace cmeans_detail

template <class S>
Status cmeans_initial_partition(std::span<const Vec3T<S>> x, int c,
                                std::span<std::uint8_t> labels) {
  PETRA_TRY(cmeans_detail::check_sizes(x.size(), labels.size(), c));
  // The ordering key: the component sum (eq. 9), or the widest component when
  // every sum is equal.
  int key = -1;  // -1: the sum; 0..2: one component
  auto value = [&](std::size_t i) {
    return key < 0 ? S(x[i](0) + x[i](1) + x[i](2)) : S(x[i](key));
  };
  S lo = value(0), hi = lo;
  for (std::size_t i = 1; i < x.size(); ++i) {
    const S v = value(i);
    lo = v < lo ? v : lo;
    hi = v > hi ? v : hi;
  }
  if (!(hi > lo)) {
    S best_range(0);
    for (int k = 0; k < 3; ++k) {
      S mn = x[0](k), mx = mn;
      for (std::size_t i = 1; i < x.size(); ++i) {
        mn = x[i](k) < mn ? x[i](k) : mn;
        mx = x[i](k) > mx ? x[i](k) : mx;
      }
      if (mx - mn > best_range) {
        best_range = mx - mn;
        key = k;
        lo = mn;
        hi = mx;
      }
    }
    if (key < 0)
      return Error::make(Errc::degenerate, "c-means: all %zu samples are equal", x.size());
  }
  const S cm1(c - 1);
  const S half(0.5);
  for (std::size_t i = 0; i < x.size(); ++i) {
    const S a = cm1 * (value(i) - lo) / (hi - lo) + S(1);  // eq. 9, 1 <= a <= c
    int cls = static_cast<int>(a + half);                  // round half up
    cls = cls < 1 ? 1 : (cls > c ? c : cls);
    labels[i] = static_cast<std::uint8_t>(cls - 1);
  }
  return {};
}

template <class S>
Result<CMeansResultT<S>> cmeans(std::span<const Vec3T<S>> x, int c, const CMeansParams& params,
                                std::span<std::uint8_t> labels) {
  using std::log;
  PETRA_TRY(validate(params));
  PETRA_TRY(cmeans_initial_partition<S>(x, c, labels));
  const std::size_t n = x.size();
  CMeansResultT<S> out;
  out.c = c;

  // Regulariser from the spread of all samples.
  S lambda;
  {
    CMeansClassT<S> all;
    Vec3T<S> sum = Vec3T<S>::Zero();
    for (const auto& v : x) sum += v;
    all.mean = sum / from_count<S>(n);
    S trace(0);
    for (const auto& v : x) trace += (v - all.mean).squaredNorm();
    trace /= from_count<S>(n);
    lambda = S(params.regularisation) * trace / S(3);
    if (!(lambda > S(0))) lambda = Eigen::NumTraits<S>::epsilon();
  }

  // Empty classes take the sample farthest (Mahalanobis) from its own class;
  // statistics are refreshed after each move.
  auto repair_empty = [&]() -> Status {
    cmeans_detail::class_statistics<S>(x, labels, c, out.classes);
    for (int j = 0; j < c; ++j) {
      if (out.classes[j].count > 0) continue;
      std::size_t worst = n;
      S worst_d(0);
      for (std::size_t i = 0; i < n; ++i) {
        const CMeansClassT<S>& own = out.classes[labels[i]];
        if (own.count <= 1) continue;
        Mat3T<S> cov = own.covariance;
        cov.diagonal().array() += lambda;
        const S d = ldlt3<S>(cov).mahalanobis(x[i] - own.mean);
        if (worst == n || d > worst_d) {
          worst = i;
          worst_d = d;
        }
      }
      if (worst == n)
        return Error::make(Errc::degenerate, "c-means: class %d is empty and no sample can move",
                           j);
      labels[worst] = static_cast<std::uint8_t>(j);
      ++out.reseeded;
      cmeans_detail::class_statistics<S>(x, labels, c, out.classes);
    }
    return {};
  };

  const S log_n = log(from_count<S>(n));
  Ldlt3<S> factor[kMaxClasses];
  S bias[kMaxClasses];  // ln|Sigma_j| - 2 ln(n_j / N)
  for (int it = 0; it < params.max_iterations; ++it) {
    PETRA_TRY(repair_empty());
    for (int j = 0; j < c; ++j) {
      CMeansClassT<S>& k = out.classes[j];
      k.covariance.diagonal().array() += lambda;
      factor[j] = ldlt3<S>(k.covariance);
      if (!factor[j].positive) {
        // Regularised covariance still not positive definite: numerically
        // impossible in double; in a coarse Q format, fall back to lambda I.
        k.covariance = Mat3T<S>::Identity() * lambda;
        factor[j] = ldlt3<S>(k.covariance);
      }
      bias[j] = factor[j].log_det() - S(2) * (log(from_count<S>(k.count)) - log_n);
    }
    // Eq. 11 assignment.
    std::size_t moved = 0;
    for (std::size_t i = 0; i < n; ++i) {
      int best = 0;
      S best_d = bias[0] + factor[0].mahalanobis(x[i] - out.classes[0].mean);
      for (int j = 1; j < c; ++j) {
        const S d = bias[j] + factor[j].mahalanobis(x[i] - out.classes[j].mean);
        if (d < best_d) {
          best_d = d;
          best = j;
        }
      }
      if (best != labels[i]) {
        labels[i] = static_cast<std::uint8_t>(best);
        ++moved;
      }
    }
    out.iterations = it + 1;
    if (moved == 0) {
      out.converged = true;
      break;
    }
  }
  // Eq. 12: the final centres (and covariances) of the final partition; an
  // unconverged last pass may have emptied a class.
  PETRA_TRY(repair_empty());
  for (int j = 0; j < c; ++j) out.classes[j].covariance.diagonal().array() += lambda;
  return out;
}

}  // namespace petra
