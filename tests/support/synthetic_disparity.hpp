// The exact rectified disparity map of a ray-cast scene (synthetic_scene.hpp)
// for a rectified pair: what a perfect matcher would output, quantised to Q4,
// optionally with Gaussian disparity noise. Header-only; tests may allocate.
#pragma once

#include <random>
#include <vector>

#include "algo/camera/rectify_geometry.hpp"
#include "algo/core/disparity.hpp"
#include "tests/support/synthetic_scene.hpp"

namespace petra::test {

struct SyntheticDisparity {
  Rect roi;
  std::vector<std::int16_t> q4;
  std::vector<int> surface;  // per pixel: -1 ground, face index, -2 no hit
  ConstDisparityMap view() const {
    return {ImageView<const std::int16_t>(q4.data(), roi.w, roi.h), roi};
  }
};

inline PinholeView rectified_view(const RectifiedCamera& c) {
  PinholeView v;
  v.f_px = c.f_px;
  v.cx = c.cx_px;
  v.cy = c.cy_px;
  v.R = c.R;
  v.T = c.T_mm;
  return v;
}

inline SyntheticDisparity render_disparity(const RectifiedPair& pair, const Rect& roi,
                                           const Rock& rock, double noise_px = 0.0,
                                           std::uint64_t seed = 1) {
  SyntheticDisparity out;
  out.roi = roi;
  const std::size_t size = static_cast<std::size_t>(roi.w) * static_cast<std::size_t>(roi.h);
  out.q4.assign(size, kInvalidDisparity);
  out.surface.assign(size, -2);
  const Cloud cloud = render(rectified_view(pair.left), roi, rock);
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, noise_px);
  for (std::size_t i = 0; i < cloud.xyz.size(); ++i) {
    auto p = rectified_project(pair, cloud.xyz[i]);
    if (!p) continue;
    const std::size_t at =
        static_cast<std::size_t>(cloud.px[i].v - roi.y) * static_cast<std::size_t>(roi.w) +
        static_cast<std::size_t>(cloud.px[i].u - roi.x);
    out.q4[at] = disparity_q4(p->disparity + (noise_px > 0 ? noise(rng) : 0.0));
    out.surface[at] = cloud.surface[i];
  }
  return out;
}

// The rectified-image bounding box of the ridge rock, padded by `pad` px.
inline Rect rock_box(const RectifiedPair& pair, const Rock& rock, double half_x, double half_y,
                     double height, int pad) {
  (void)rock;
  const PinholeView v = rectified_view(pair.left);
  double u0 = 1e9, v0 = 1e9, u1 = -1e9, v1 = -1e9;
  for (double x : {-half_x, half_x})
    for (double y : {-half_y, half_y})
      for (double z : {0.0, height}) {
        const Eigen::Vector2d p = v.project({x, y, z});
        u0 = std::min(u0, p.x());
        v0 = std::min(v0, p.y());
        u1 = std::max(u1, p.x());
        v1 = std::max(v1, p.y());
      }
  return Rect{static_cast<int>(u0) - pad, static_cast<int>(v0) - pad,
              static_cast<int>(u1 - u0) + 2 * pad, static_cast<int>(v1 - v0) + 2 * pad};
}

}  // namespace petra::test
