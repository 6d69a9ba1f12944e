// Template body of segment_ground (algo/ground_segment.hpp). Included by that
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

}  // namespace ground_detail

template <class S>
Result<GroundResultT<S>> segment_ground(std::span<const Vec3T<S>> xyz, std::span<const PixelPos> px,
                                        const Rect& roi, const ClickPx& click,
                                        const Vec3T<S>& camera, const GroundParams& params,
                                        std::span<PointClass> labels) {
  using ground_detail::abs_s;
  using ground_detail::max_s;
  using std::sqrt;
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

  // The clicked point, if any.
  if (click.present) {
    if (!roi.contains(click.u, click.v))
      return Error::make(Errc::out_of_range,
                         "segmentation: click (%d, %d) outside the ROI (%d, %d %dx%d)", click.u,
                         click.v, roi.x, roi.y, roi.w, roi.h);
    const std::size_t c = ground_detail::nearest_pixel(px, click.u, click.v);
    const double du = px[c].u - click.u, dv = px[c].v - click.v;
    if (du * du + dv * dv > double(params.click_radius_px) * params.click_radius_px)
      return Error::make(Errc::no_solution,
                         "segmentation: no 3-D point within %d px of the click (%d, %d): shadow or "
                         "no match there",
                         params.click_radius_px, click.u, click.v);
    out.click_point = c;
  }

  // 1. Seed plane from three points near the bottom corners.
  const double x0 = roi.x, x1 = roi.x + roi.w - 1, y1 = roi.y + roi.h - 1;
  const double y_up = y1 - roi.h / 4.0;
  const double reach2 = 0.0625 * (double(roi.w) * roi.w + double(roi.h) * roi.h);  // (diag/4)^2
  const std::size_t bl = ground_detail::nearest_pixel(px, x0, y1);
  const std::size_t br = ground_detail::nearest_pixel(px, x1, y1);
  const std::size_t ul = ground_detail::nearest_pixel(px, x0, y_up);
  const std::size_t ur = ground_detail::nearest_pixel(px, x1, y_up);
  auto too_far = [&](std::size_t i, double u, double v) {
    const double du = px[i].u - u, dv = px[i].v - v;
    return du * du + dv * dv > reach2;
  };
  if (too_far(bl, x0, y1) || too_far(br, x1, y1))
    return Error::make(Errc::no_solution,
                       "segmentation: no points near the ROI's bottom corners (no ground seed)");
  const Vec3T<S>& a = xyz[bl];
  const Vec3T<S>& b = xyz[br];
  const Vec3T<S> nl = (b - a).cross(xyz[ul] - a);
  const Vec3T<S> nr = (b - a).cross(xyz[ur] - a);
  const bool use_left = nl.squaredNorm() >= nr.squaredNorm();
  const std::size_t third = use_left ? ul : ur;
  Vec3T<S> normal = use_left ? nl : nr;
  const S base = sqrt((b - a).squaredNorm()) * sqrt((xyz[third] - a).squaredNorm());
  const S cross_len = sqrt(normal.squaredNorm());
  // sin of the angle at a below 1e-3: the three seeds are collinear.
  if (!(base > S(0)) || !(cross_len > base * S(1e-3)) || too_far(third, use_left ? x0 : x1, y_up))
    return Error::make(Errc::degenerate,
                       "segmentation: ground seed points near the bottom corners are collinear");
  out.seed[0] = bl;
  out.seed[1] = br;
  out.seed[2] = third;
  normal /= cross_len;
  PlaneT<S> plane;
  plane.normal = normal;
  plane.d = -normal.dot(a);
  auto orient_to_camera = [&](PlaneT<S>& p) {
    if (p.distance(camera) < S(0)) {
      p.normal = -p.normal;
      p.d = -p.d;
    }
  };
  orient_to_camera(plane);

  // 2-4. k-means on the signed distance, refit, until the plane settles; on
  // a regular sample of at most kSegmentSamples points (every pass costs
  // per point), then one full-resolution labelling and refit.
  const std::size_t stride = (n + kSegmentSamples - 1) / kSegmentSamples;
  const std::size_t samples = (n + stride - 1) / stride;
  S rock_centre{};
  {
    // Rock seed: a high quantile of the distances, not the maximum, so a few
    // far mismatches cannot take the rock cluster (1 mm bins, -64..959 mm).
    std::uint32_t hist[1024] = {};
    for (std::size_t k = 0; k < samples; ++k) {
      const int bin = static_cast<int>(plane.distance(xyz[k * stride])) + 64;
      ++hist[bin < 0 ? 0 : (bin > 1023 ? 1023 : bin)];
    }
    const std::size_t target = samples - samples / 50;  // the 98th percentile
    std::size_t seen = 0;
    int top = 0;
    for (; top < 1023 && seen + hist[top] < target; ++top) seen += hist[top];
    rock_centre = click.present ? plane.distance(xyz[out.click_point]) : S(top - 64);
  }
  S ground_centre(0);
  PlaneFitT<S> fit;
  bool have_fit = false;
  // Labels of the whole cloud (stride 1) or of the sample.
  auto kmeans = [&](std::size_t step, std::size_t count) {
    if (click.present) rock_centre = plane.distance(xyz[out.click_point]);
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
    if (click.present) labels[out.click_point] = PointClass::rock;
  };
  // The foot of the rock falls in the ground cluster (k-means on distance
  // splits at mid-height); trimming the cluster to a band of 3 RMS of the
  // previous fit keeps it out of the refit.
  auto refit = [&](std::size_t step, std::size_t count) -> Status {
    const S band_mm = have_fit ? max_s(S(3) * fit.rms, S(params.min_trim_band_mm)) : S(1e6);
    auto f = fit_plane_tls_by<S>(
        count, [&](std::size_t k) -> const Vec3T<S>& { return xyz[k * step]; },
        [&](std::size_t k) {
          return labels[k * step] == PointClass::ground &&
                 abs_s(plane.distance(xyz[k * step])) <= band_mm;
        });
    if (!f)
      return Error::make(Errc::no_solution, "segmentation: no ground plane in the ROI (%s)",
                         f.error().message);
    fit = *f;
    have_fit = true;
    return {};
  };
  for (int it = 0; it < params.max_iterations; ++it) {
    out.iterations = it + 1;
    kmeans(stride, samples);
    PETRA_TRY(refit(stride, samples));
    PlaneT<S> next = fit.plane;
    orient_to_camera(next);
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
    PETRA_TRY(refit(1, n));
    plane = fit.plane;
    orient_to_camera(plane);
  }
  PETRA_ASSERT(have_fit);

  // Final labels about the final plane: ground is the band of noise around
  // it (3 RMS, at least min_ground_band_mm), everything above is rock. The
  // k-means midpoint found the plane; as a label it would give the lower
  // half of the rock's faces to the ground.
  std::size_t ng = 0, nr_ = 0, band_total = 0, band_ground = 0, below = 0;
  const S deep = -S(params.min_rock_height_mm);
  S sum_r(0);
  S split = max_s(S(params.ground_band_rms) * fit.rms, S(params.min_ground_band_mm));
  if (rock_centre / S(2) < split) split = rock_centre / S(2);
  const int band = static_cast<int>(params.border_band * (roi.w < roi.h ? roi.w : roi.h)) + 1;
  for (std::size_t i = 0; i < n; ++i) {
    const S d = plane.distance(xyz[i]);
    const PointClass c = d > split ? PointClass::rock : PointClass::ground;
    labels[i] = c;
    if (c == PointClass::rock) {
      ++nr_;
      sum_r += d;
    } else {
      ++ng;
    }
    below += d < deep;
    const int u = px[i].u, v = px[i].v;
    if (u < roi.x + band || v < roi.y + band || u >= roi.x + roi.w - band ||
        v >= roi.y + roi.h - band) {
      ++band_total;
      band_ground += c == PointClass::ground;
    }
  }
  if (click.present && labels[out.click_point] != PointClass::rock)
    return Error::make(Errc::no_solution,
                       "segmentation: the clicked point lies on the ground plane, not on a rock");
  out.plane = plane;
  out.rms_mm = fit.rms;
  out.ground_points = ng;
  out.rock_points = nr_;
  out.rock_centre_mm = nr_ > 0 ? sum_r / from_count<S>(nr_) : S(0);
  if (nr_ == 0 || !(out.rock_centre_mm >= S(params.min_rock_height_mm)))
    return Error::make(Errc::degenerate,
                       "segmentation: no rock: the points lie on one plane (rock centre %.2f mm "
                       "above it, need %.2f)",
                       to_double(out.rock_centre_mm), params.min_rock_height_mm);
  if (!(fit.rms <= S(params.max_ground_rms_mm)))
    return Error::make(Errc::no_solution,
                       "segmentation: no ground in the ROI: best plane has RMS %.2f mm > %.2f",
                       to_double(fit.rms), params.max_ground_rms_mm);
  // Nothing stands below the ground: a plane with much beneath it is a face
  // of a rock that fills the ROI.
  if (double(below) > params.max_below_fraction * double(n))
    return Error::make(
        Errc::no_solution,
        "segmentation: no ground in the ROI: %zu of %zu points lie more than %.1f mm "
        "below the best plane",
        below, n, params.min_rock_height_mm);
  if (double(ng) < params.min_ground_fraction * double(n))
    return Error::make(
        Errc::no_solution,
        "segmentation: no ground in the ROI: only %zu of %zu points on the ground plane", ng, n);
  if (band_total > 0 && double(band_ground) < params.min_border_ground * double(band_total))
    return Error::make(Errc::no_solution,
                       "segmentation: no ground in the ROI: %zu of %zu border points are ground; "
                       "is the ROI inside the rock?",
                       band_ground, band_total);
  return out;
}

}  // namespace petra
