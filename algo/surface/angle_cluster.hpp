// Clustering of unit normals by angle (docs/method.md 4b steps 3-4), over a scalar
// type S (double or Fixed<F>):
//   - initial centres: the given ones (normalised), kept only when more than
//     min_separation_deg from every centre kept before; a centre that is too
//     close is replaced by the normal farthest from the kept centres, and
//     dropped when even that one is too close (fewer distinct directions than
//     asked: the result's c says how many remain);
//   - each normal joins the centre at the smallest angle (largest cosine; no
//     trigonometry in the loop);
//   - new centre = weighted mean normal of its class, renormalised;
//   - stop when no normal changes class (the centres then stop moving
//     exactly), or after max_iterations.
// Weights are the triangle areas in grind_planes (a plain mean with all ones).
// Output: a class per normal into a caller span. No heap, no scratch.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>

#include "algo/core/result.hpp"
#include "algo/mesh/linalg3.hpp"
#include "algo/surface/cmeans.hpp"

namespace petra {

struct AngleClusterParams {
  double min_separation_deg = 5.0;
  int max_iterations = 100;
};

template <class S>
struct AngleClusterResultT {
  Vec3T<S> centres[kMaxClasses];
  S weight[kMaxClasses] = {};
  std::size_t count[kMaxClasses] = {};
  int c = 0;  // centres kept (<= the number given)
  int iterations = 0;
  bool converged = false;
};

template <class S>
Result<AngleClusterResultT<S>> angle_cluster(std::span<const Vec3T<S>> normals,
                                             std::span<const S> weights,
                                             std::span<const Vec3T<S>> initial_centres,
                                             const AngleClusterParams& params,
                                             std::span<std::uint8_t> labels) {
  using std::sqrt;
  const std::size_t n = normals.size();
  const int c_in = static_cast<int>(initial_centres.size());
  if (c_in < 1 || c_in > kMaxClasses)
    return Error::make(Errc::out_of_range, "angle clustering: %d centres, must be 1..%d", c_in,
                       kMaxClasses);
  if (weights.size() != n || labels.size() != n)
    return Error::make(Errc::invalid_argument,
                       "angle clustering: %zu normals, %zu weights, %zu labels", n, weights.size(),
                       labels.size());
  if (n == 0) return Error::make(Errc::degenerate, "angle clustering: no normals");
  if (!(params.min_separation_deg >= 0.0 && params.min_separation_deg < 90.0) ||
      params.max_iterations < 1)
    return Error::make(
        Errc::invalid_argument,
        "angle clustering: min_separation_deg %.3g not in [0, 90) or max_iterations %d",
        params.min_separation_deg, params.max_iterations);
  const S cos_sep(std::cos(params.min_separation_deg * M_PI / 180.0));
  AngleClusterResultT<S> out;
  auto normalised = [&](const Vec3T<S>& v) -> Vec3T<S> {
    const S len = sqrt(v.squaredNorm());
    return len > S(0) ? Vec3T<S>(v / len) : Vec3T<S>::UnitZ();
  };
  // Largest cosine to the centres kept so far.
  auto nearest_cos = [&](const Vec3T<S>& v) {
    S best(-2);
    for (int k = 0; k < out.c; ++k) {
      const S d = v.dot(out.centres[k]);
      best = d > best ? d : best;
    }
    return best;
  };
  for (int j = 0; j < c_in; ++j) {
    Vec3T<S> centre = normalised(initial_centres[j]);
    if (out.c > 0 && !(nearest_cos(centre) < cos_sep)) {
      // Too close: take the normal farthest from the kept centres instead.
      std::size_t far = 0;
      S far_cos = nearest_cos(normals[0]);
      for (std::size_t i = 1; i < n; ++i) {
        const S d = nearest_cos(normals[i]);
        if (d < far_cos) {
          far_cos = d;
          far = i;
        }
      }
      if (!(far_cos < cos_sep)) continue;  // nothing distinct left: drop it
      centre = normalised(normals[far]);
    }
    out.centres[out.c++] = centre;
  }

  for (std::size_t i = 0; i < n; ++i) labels[i] = 0xFF;
  for (int it = 0; it < params.max_iterations; ++it) {
    std::size_t moved = 0;
    Vec3T<S> sum[kMaxClasses];
    for (int k = 0; k < out.c; ++k) {
      sum[k] = Vec3T<S>::Zero();
      out.weight[k] = S(0);
      out.count[k] = 0;
    }
    for (std::size_t i = 0; i < n; ++i) {
      int best = 0;
      S best_cos = normals[i].dot(out.centres[0]);
      for (int k = 1; k < out.c; ++k) {
        const S d = normals[i].dot(out.centres[k]);
        if (d > best_cos) {
          best_cos = d;
          best = k;
        }
      }
      if (labels[i] != best) {
        labels[i] = static_cast<std::uint8_t>(best);
        ++moved;
      }
      sum[best] += weights[i] * normals[i];
      out.weight[best] += weights[i];
      ++out.count[best];
    }
    out.iterations = it + 1;
    if (moved == 0) {
      out.converged = true;
      break;
    }
    for (int k = 0; k < out.c; ++k)
      if (out.count[k] > 0) out.centres[k] = normalised(sum[k]);
  }
  return out;
}

}  // namespace petra
