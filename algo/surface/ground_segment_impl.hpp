// Template body of segment_ground (algo/surface/ground_segment.hpp). Included by that
// header only; double is instantiated once in ground_segment.cpp.
#pragma once

#include <Eigen/Geometry>
#include <cmath>

namespace petra {

namespace ground_detail {

// Index of the point nearest (in pixels) to (u, v), or points.size().
inline std::size_t nearest_pixel(std::span<const PixelPos> px, double u, double v) {
  std::size_t best = px.size();
  double best_d2 = 0;
  for (std::size_t i = 0; i < px.size(); ++i) {
    const double du = px[i].u - u, dv = px[i].v - v;
    const double d2 = du * du + dv * dv;
    if (best == px.size() || d2 < best_d2) {
      best = i;
      best_d2 = d2;
    }
  }
  return best;
}

template <class S>
S abs_s(S x) {
  return x < S(0) ? -x : x;
}
template <class S>
S max_s(S a, S b) {
  return a < b ? b : a;
}

// SplitMix64: a tiny deterministic generator (fixed seed, no state beyond one word).
struct SplitMix {
  std::uint64_t state;
  std::uint64_t next() {
    std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  std::size_t below(std::size_t n) { return static_cast<std::size_t>(next() % n); }
};

inline bool in_border_band(const PixelPos& p, const Rect& roi, int band) {
  return p.u < roi.x + band || p.v < roi.y + band || p.u >= roi.x + roi.w - band ||
         p.v >= roi.y + roi.h - band;
}

// A random point of the border band (rejection sampling, bounded), else any point.
inline std::size_t draw_border_point(SplitMix& rng, std::span<const PixelPos> px, const Rect& roi,
                                     int band) {
  std::size_t i = rng.below(px.size());
  for (int tries = 0; tries < 64 && !in_border_band(px[i], roi, band); ++tries)
    i = rng.below(px.size());
  return i;
}

// Plane through a, b, c oriented towards the camera; false when they are
// (nearly) collinear: sin of the angle at a below 1e-3.
template <class S>
bool plane_through(const Vec3T<S>& a, const Vec3T<S>& b, const Vec3T<S>& c, const Vec3T<S>& camera,
                   PlaneT<S>& out) {
  using std::sqrt;
  Vec3T<S> n = (b - a).cross(c - a);
  const S base = sqrt((b - a).squaredNorm()) * sqrt((c - a).squaredNorm());
  const S len = sqrt(n.squaredNorm());
  if (!(base > S(0)) || !(len > base * S(1e-3))) return false;
  n /= len;
  out.normal = n;
  out.d = -n.dot(a);
  if (out.distance(camera) < S(0)) {
    out.normal = -out.normal;
    out.d = -out.d;
  }
  return true;
}

// MSAC cost of a plane over every step-th point: min(d^2, T^2), and
// below_cost * T^2 for a point more than T under it.
template <class S>
S msac_cost(const PlaneT<S>& plane, std::span<const Vec3T<S>> xyz, std::size_t step, S t,
            S below_cost) {
  const S t2 = t * t;
  S cost(0);
  for (std::size_t i = 0; i < xyz.size(); i += step) {
    const S d = plane.distance(xyz[i]);
    if (d < -t)
      cost += below_cost * t2;
    else
      cost += d * d < t2 ? d * d : t2;
  }
  return cost;
}

struct MsacSeed {
  bool found = false;
  std::size_t seed[3] = {0, 0, 0};
};

// The best of a bounded number of random border triples (docs/method.md 2a step 1, Petra's MSAC).
template <class S>
MsacSeed msac_seed(std::span<const Vec3T<S>> xyz, std::span<const PixelPos> px, const Rect& roi,
                   int band, const Vec3T<S>& camera, S t, const GroundParams& params,
                   PlaneT<S>& plane) {
  constexpr std::size_t kScored = 1024;  // points each candidate is scored on
  const std::size_t step = (xyz.size() + kScored - 1) / kScored;
  SplitMix rng{params.msac_seed};
  MsacSeed out;
  S best{};
  for (int it = 0; it < params.msac_iterations; ++it) {
    const std::size_t i = draw_border_point(rng, px, roi, band);
    const std::size_t j = draw_border_point(rng, px, roi, band);
    const std::size_t k = draw_border_point(rng, px, roi, band);
    PlaneT<S> candidate;
    if (!plane_through(xyz[i], xyz[j], xyz[k], camera, candidate)) continue;
    const S cost = msac_cost(candidate, xyz, step, t, S(params.below_cost));
    if (out.found && !(cost < best)) continue;
    best = cost;
    plane = candidate;
    out = {true, {i, j, k}};
  }
  return out;
}

// Mean distance of every step-th point to the camera (the range of the noise model).
template <class S>
double mean_range_mm(std::span<const Vec3T<S>> xyz, std::size_t step, const Vec3T<S>& camera) {
  using std::sqrt;
  double sum = 0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < xyz.size(); i += step, ++n)
    sum += to_double(sqrt((xyz[i] - camera).squaredNorm()));
  return n > 0 ? sum / static_cast<double>(n) : 0.0;
}

// Records why the cloud is not ground, for a caller that may segment from
// the click instead.
inline Error fail(GroundFailure* failure, GroundFailure why, const Error& e) {
  if (failure != nullptr) *failure = why;
  return e;
}

template <class S>
void orient_to_camera(PlaneT<S>& p, const Vec3T<S>& camera) {
  if (p.distance(camera) < S(0)) {
    p.normal = -p.normal;
    p.d = -p.d;
  }
}

// The point of the cloud under the click: the nearest within click_radius_px.
inline Result<std::size_t> clicked_point(std::span<const PixelPos> px, const Rect& roi,
                                         const ClickPx& click, const GroundParams& params) {
  if (!roi.contains(click.u, click.v))
    return Error::make(Errc::out_of_range, "the click (%d, %d) is outside the ROI (%d, %d %dx%d)",
                       click.u, click.v, roi.x, roi.y, roi.w, roi.h);
  const std::size_t c = nearest_pixel(px, click.u, click.v);
  const double du = px[c].u - click.u, dv = px[c].v - click.v;
  if (du * du + dv * dv > double(params.click_radius_px) * params.click_radius_px)
    return Error::make(Errc::no_solution,
                       "no depth within %d px of the click (%d, %d): shadow or no match "
                       "there; click elsewhere on the rock",
                       params.click_radius_px, click.u, click.v);
  return c;
}

// Depth noise at the cloud's mean range (the stereo model) with the
// terrain's roughness: out.sigma_z_mm and out.sigma_mm.
template <class S>
void noise_sigmas(std::span<const Vec3T<S>> xyz, const Vec3T<S>& camera, const StereoNoise& noise,
                  const GroundParams& params, GroundResultT<S>& out) {
  const std::size_t n = xyz.size();
  const double r = mean_range_mm(xyz, (n + 1023) / 1024, camera);
  const double fb = noise.focal_px * noise.baseline_mm;
  out.sigma_z_mm = fb > 0 ? r * r * params.sigma_disparity_px / fb : 0.0;
  out.sigma_mm = std::sqrt(out.sigma_z_mm * out.sigma_z_mm +
                           params.terrain_roughness_mm * params.terrain_roughness_mm);
}

// Rock seed: a high quantile of the sample's distances to the plane, not
// the maximum, so a few far mismatches cannot take the rock cluster (1 mm
// bins, -64..959 mm).
template <class S>
S rock_seed_mm(std::span<const Vec3T<S>> xyz, std::size_t stride, std::size_t samples,
               const PlaneT<S>& plane) {
  std::uint32_t hist[1024] = {};
  for (std::size_t k = 0; k < samples; ++k) {
    const int bin = static_cast<int>(plane.distance(xyz[k * stride])) + 64;
    ++hist[bin < 0 ? 0 : (bin > 1023 ? 1023 : bin)];
  }
  const std::size_t target = samples - samples / 50;  // the 98th percentile
  std::size_t seen = 0;
  int top = 0;
  for (; top < 1023 && seen + hist[top] < target; ++top) seen += hist[top];
  return S(top - 64);
}

// Steps 2-4: k-means on the signed distance and the ground plane's refit,
// over every step-th point of the cloud.
template <class S>
struct GroundFit {
  std::span<const Vec3T<S>> xyz;
  std::span<PointClass> labels;
  const ClickPx& click;
  std::size_t click_point = 0;
  const GroundParams& params;
  S inlier_band{};
  PlaneT<S> plane{};
  S rock_centre{};
  S ground_centre{};
  PlaneFitT<S> fit{};
  bool have_fit = false;

  // Labels of the whole cloud (stride 1) or of the sample.
  void kmeans(std::size_t step, std::size_t count) {
    if (click.present) rock_centre = plane.distance(xyz[click_point]);
    ground_centre = S(0);
    if (!(rock_centre > ground_centre)) rock_centre = ground_centre + S(params.min_rock_height_mm);
    for (int pass = 0; pass < params.max_kmeans_passes; ++pass) {
      S sum_g(0), sum_r(0);
      std::size_t ng = 0, nr_ = 0, moved = 0;
      const S split = (ground_centre + rock_centre) / S(2);
      for (std::size_t k = 0; k < count; ++k) {
        const std::size_t i = k * step;
        const S d = plane.distance(xyz[i]);
        const PointClass c = d > split ? PointClass::rock : PointClass::ground;
        if (pass == 0 || c != labels[i]) ++moved;
        labels[i] = c;
        if (c == PointClass::rock) {
          sum_r += d;
          ++nr_;
        } else {
          sum_g += d;
          ++ng;
        }
      }
      if (ng > 0) ground_centre = sum_g / from_count<S>(ng);
      if (nr_ > 0) rock_centre = sum_r / from_count<S>(nr_);
      if (moved == 0 || nr_ == 0) break;
    }
    if (click.present) labels[click_point] = PointClass::rock;
  }

  // The foot of the rock falls in the ground cluster (k-means on distance
  // splits at mid-height); trimming the cluster to a band of 3 RMS of the
  // previous fit keeps it out of the refit.
  Status refit(std::size_t step, std::size_t count, GroundFailure* failure) {
    const S band_mm = have_fit ? max_s(S(3) * fit.rms, S(params.min_trim_band_mm)) : inlier_band;
    auto f = fit_plane_tls_by<S>(
        count, [&](std::size_t k) -> const Vec3T<S>& { return xyz[k * step]; },
        [&](std::size_t k) {
          return labels[k * step] == PointClass::ground &&
                 abs_s(plane.distance(xyz[k * step])) <= band_mm;
        });
    if (!f)
      return fail(failure, GroundFailure::no_ground,
                  Error::make(Errc::no_solution, "no ground in the ROI: no plane fits (%s)",
                              f.error().message));
    fit = *f;
    have_fit = true;
    return {};
  }

  // Iterates on a regular sample of at most kSegmentSamples points (every
  // pass costs per point) until the plane settles, then labels and refits
  // the whole cloud once.
  Status settle(const Vec3T<S>& camera, GroundFailure* failure, GroundResultT<S>& out) {
    using std::sqrt;
    const std::size_t n = xyz.size();
    const std::size_t stride = (n + kSegmentSamples - 1) / kSegmentSamples;
    const std::size_t samples = (n + stride - 1) / stride;
    rock_centre = click.present ? plane.distance(xyz[click_point])
                                : rock_seed_mm(xyz, stride, samples, plane);
    for (int it = 0; it < params.max_iterations; ++it) {
      out.iterations = it + 1;
      kmeans(stride, samples);
      PETRA_TRY(refit(stride, samples, failure));
      PlaneT<S> next = fit.plane;
      orient_to_camera(next, camera);
      const Vec3T<S> dn = next.normal - plane.normal;
      const S dd = next.d - plane.d;
      const S change = sqrt(dn.squaredNorm() + dd * dd);
      plane = next;
      if (change < S(params.epsilon)) {
        out.converged = true;
        break;
      }
    }
    if (stride > 1) {
      kmeans(1, n);
      PETRA_TRY(refit(1, n, failure));
      plane = fit.plane;
      orient_to_camera(plane, camera);
    }
    PETRA_ASSERT(have_fit);
    return {};
  }
};

// Counts of the final labelling.
struct FinalLabels {
  std::size_t ground = 0, rock = 0;
  std::size_t band_total = 0, band_ground = 0;  // in the ROI's border band
  std::size_t below = 0;                        // more than below_mm under the plane
  double below_mm = 0;
};

// Final labels about the final plane: ground is the band of noise around
// it (3 measured RMS, at least min_ground_band_mm), everything above is
// rock (a wider band from the noise model took the foot of steep faces). The k-means midpoint
// found the plane; as a label it would give the lower half of the rock's faces to the ground.
template <class S>
FinalLabels final_labels(const GroundFit<S>& g, std::span<const PixelPos> px, const Rect& roi,
                         int band, GroundResultT<S>& out) {
  const std::span<const Vec3T<S>> xyz = g.xyz;
  const std::span<PointClass> labels = g.labels;
  FinalLabels f;
  f.below_mm = std::max(g.params.min_rock_height_mm, to_double(g.inlier_band));
  const S deep = -S(f.below_mm);
  S sum_r(0);
  S split = max_s(S(g.params.ground_band_rms) * g.fit.rms, S(g.params.min_ground_band_mm));
  if (g.rock_centre / S(2) < split) split = g.rock_centre / S(2);
  for (std::size_t i = 0; i < xyz.size(); ++i) {
    const S d = g.plane.distance(xyz[i]);
    const PointClass c = d > split ? PointClass::rock : PointClass::ground;
    labels[i] = c;
    if (c == PointClass::rock) {
      ++f.rock;
      sum_r += d;
    } else {
      ++f.ground;
    }
    f.below += d < deep;
    if (in_border_band(px[i], roi, band)) {
      ++f.band_total;
      f.band_ground += c == PointClass::ground;
    }
  }
  out.plane = g.plane;
  out.rms_mm = g.fit.rms;
  out.ground_points = f.ground;
  out.rock_points = f.rock;
  out.rock_centre_mm = f.rock > 0 ? sum_r / from_count<S>(f.rock) : S(0);
  return f;
}

// Is it ground? Refusals in the operator's terms; the caller may segment
// from the click instead.
template <class S>
Status ground_verdict(const FinalLabels& f, const GroundFit<S>& g, const GroundResultT<S>& out,
                      GroundFailure* failure) {
  const GroundParams& params = g.params;
  const std::size_t n = g.xyz.size();
  const double rms_limit = params.max_rms_sigmas * out.sigma_mm;
  if (!(to_double(g.fit.rms) <= rms_limit))
    return fail(failure, GroundFailure::no_ground,
                Error::make(Errc::no_solution,
                            "no ground in the ROI: the flattest surface is %.1f mm rough (ground: "
                            "up to %.1f)",
                            to_double(g.fit.rms), rms_limit));
  // Nothing stands below the ground: a plane with much beneath it is a face
  // of a rock that fills the ROI.
  if (double(f.below) > params.max_below_fraction * double(n))
    return fail(
        failure, GroundFailure::no_ground,
        Error::make(Errc::no_solution,
                    "no ground in the ROI: %zu of %zu points lie %.1f mm below the flattest "
                    "surface",
                    f.below, n, f.below_mm));
  // Points on one plane: no rock (checked once the plane is known to be ground-like).
  if (f.rock == 0 || !(out.rock_centre_mm >= S(params.min_rock_height_mm)))
    return Error::make(Errc::degenerate,
                       "no rock: the points lie on one plane (rock centre %.2f mm above it, "
                       "need %.2f)",
                       to_double(out.rock_centre_mm), params.min_rock_height_mm);
  if (double(f.ground) < params.min_ground_fraction * double(n))
    return fail(
        failure, GroundFailure::no_ground,
        Error::make(Errc::no_solution,
                    "no ground in the ROI: only %zu of %zu points on a ground plane", f.ground, n));
  if (f.band_total > 0 && double(f.band_ground) < params.min_border_ground * double(f.band_total))
    return fail(failure, GroundFailure::no_ground,
                Error::make(Errc::no_solution,
                            "no ground in the ROI: %zu of %zu border points are ground; the rock "
                            "fills the ROI",
                            f.band_ground, f.band_total));
  if (g.click.present && g.labels[g.click_point] != PointClass::rock)
    return fail(
        failure, GroundFailure::click_on_ground,
        Error::make(Errc::no_solution, "no rock under the click: the click is on the ground"));
  // A rock stands clear of the ground's relief; a surface whose "rock" is
  // within a few RMS of it is a gently folded rock top (a roof), not ground.
  const double clear_mm = params.min_rock_height_rms * to_double(g.fit.rms);
  if (!(to_double(out.rock_centre_mm) >= clear_mm))
    return fail(failure, GroundFailure::no_ground,
                Error::make(Errc::no_solution,
                            "no ground in the ROI: nothing stands clear of the flattest surface "
                            "(%.1f mm, need %.1f)",
                            to_double(out.rock_centre_mm), clear_mm));
  return {};
}

}  // namespace ground_detail

template <class S>
Result<GroundResultT<S>> segment_ground(std::span<const Vec3T<S>> xyz, std::span<const PixelPos> px,
                                        const Rect& roi, const ClickPx& click,
                                        const Vec3T<S>& camera, const GroundParams& params,
                                        std::span<PointClass> labels, const StereoNoise& noise,
                                        GroundFailure* failure) {
  PETRA_TRY(validate(params));
  const std::size_t n = xyz.size();
  if (px.size() != n || labels.size() != n)
    return Error::make(Errc::invalid_argument,
                       "segmentation: %zu positions, %zu pixels, %zu labels differ", n, px.size(),
                       labels.size());
  if (roi.empty()) return Error::make(Errc::invalid_argument, "segmentation: empty ROI");
  if (n < params.min_points)
    return Error::make(Errc::degenerate, "segmentation: %zu points, need at least %zu", n,
                       params.min_points);
  GroundResultT<S> out;
  if (click.present) {
    auto c = ground_detail::clicked_point(px, roi, click, params);
    if (!c) return c.error();
    out.click_point = *c;
  }
  const int band = static_cast<int>(params.border_band * (roi.w < roi.h ? roi.w : roi.h)) + 1;

  // 1. Seed plane by MSAC, its tolerance from the depth-noise model.
  ground_detail::noise_sigmas(xyz, camera, noise, params, out);
  ground_detail::GroundFit<S> g{
      xyz, labels, click, out.click_point, params, S(params.inlier_sigmas * out.sigma_mm)};
  const ground_detail::MsacSeed seeded =
      ground_detail::msac_seed(xyz, px, roi, band, camera, g.inlier_band, params, g.plane);
  if (!seeded.found)
    return ground_detail::fail(
        failure, GroundFailure::no_ground,
        Error::make(Errc::degenerate,
                    "no ground in the ROI: the points around it are collinear (%d tries)",
                    params.msac_iterations));
  for (int k = 0; k < 3; ++k) out.seed[k] = seeded.seed[k];

  // 2-4. k-means on the signed distance, refit, until the plane settles.
  PETRA_TRY(g.settle(camera, failure, out));
  const ground_detail::FinalLabels f = ground_detail::final_labels(g, px, roi, band, out);
  PETRA_TRY(ground_detail::ground_verdict(f, g, out, failure));
  return out;
}

}  // namespace petra
