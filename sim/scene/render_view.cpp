#include "sim/scene/render_view.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "sim/scene/camera_rays.hpp"
#include "sim/scene/ray_cast.hpp"
#include "sim/scene/rng.hpp"

namespace petra::sim {

namespace {

// Noise streams (the geometry uses 1..3, see scene.cpp).
constexpr std::uint64_t kStreamNoiseLeft = 11;
constexpr std::uint64_t kStreamNoiseRight = 12;
constexpr std::uint64_t kStreamPrnuLeft = 13;
constexpr std::uint64_t kStreamPrnuRight = 14;

// The camera's response (realistic world): vignetting and pixel response
// non-uniformity on the signal, then the camera's gain and offset.
struct Response {
  bool active = false;
  double vignetting = 0, prnu = 0, gain = 1, offset = 0;
  double cx = 0, cy = 0, corner2 = 1;  // principal point, squared distance to the farthest corner
  std::uint64_t prnu_key = 0;

  Response(const Scene& s, const TsaiCamera& cam, Eye eye) {
    const World& w = s.options.world;
    const bool left = eye == Eye::left;
    vignetting = w.vignetting;
    prnu = w.prnu;
    gain = left ? w.gain_left : w.gain_right;
    offset = left ? w.offset_left_dn : w.offset_right_dn;
    active = vignetting > 0 || prnu > 0 || gain != 1 || offset != 0;
    cx = cam.cx_px;
    cy = cam.cy_px;
    const double dx = std::max(cx, cam.width - 1 - cx), dy = std::max(cy, cam.height - 1 - cy);
    corner2 = dx * dx + dy * dy;
    prnu_key = mix64(s.options.seed ^ ((left ? kStreamPrnuLeft : kStreamPrnuRight) << 56));
  }
  double signal(double dn, int i, int j, std::size_t k) const {
    const double r2 = ((i - cx) * (i - cx) + (j - cy) * (j - cy)) / corner2;
    return dn * (1.0 - vignetting * r2) * (1.0 + prnu * hashed_normal(prnu_key, k));
  }
};

struct Sample {
  int label = 0;  // surface * 2 + shadowed
  double radiance = 0;
};

class ViewRenderer {
 public:
  ViewRenderer(const Scene& scene, const TsaiCamera& cam)
      : scene_(scene), rays_(cam), angle_(pixel_angle(cam)) {}

  int label(double u, double v) const {
    const SceneHit hit = trace(scene_, rays_.origin(), rays_.direction(u, v));
    return hit.surface * 2 + (in_shadow(scene_, hit) ? 1 : 0);
  }

  Sample sample(double u, double v) const {
    const Eigen::Vector3d dir = rays_.direction(u, v);
    const SceneHit hit = trace(scene_, rays_.origin(), dir);
    const bool shadowed = in_shadow(scene_, hit);
    return {hit.surface * 2 + (shadowed ? 1 : 0), radiance(scene_, hit, shadowed, angle_, dir)};
  }

  // Mean radiance and shadowed fraction over an n x n grid in pixel (i, j).
  void integrate(int i, int j, int n, double& mean, double& shadow_fraction) const {
    double sum = 0;
    int shadowed = 0;
    for (int b = 0; b < n; ++b)
      for (int a = 0; a < n; ++a) {
        const Sample s = sample(i - 0.5 + (a + 0.5) / n, j - 0.5 + (b + 0.5) / n);
        sum += s.radiance;
        shadowed += s.label & 1;
      }
    mean = sum / (n * n);
    shadow_fraction = static_cast<double>(shadowed) / (n * n);
  }

 private:
  const Scene& scene_;
  CameraRays rays_;
  double angle_;
};

std::uint8_t quantise(double dn) {
  return static_cast<std::uint8_t>(std::clamp(std::floor(dn + 0.5), 0.0, 255.0));
}

}  // namespace

RenderedView render_view(const Scene& scene, Eye eye) {
  const TsaiCamera& cam = eye == Eye::left ? scene.rig.left : scene.rig.right;
  return render_view(scene, eye, Rect{0, 0, cam.width, cam.height});
}

RenderedView render_view(const Scene& scene, Eye eye, const Rect& window) {
  const TsaiCamera& cam = eye == Eye::left ? scene.rig.left : scene.rig.right;
  const int w = cam.width, h = cam.height;
  const int x0 = std::max(window.x, 0), y0 = std::max(window.y, 0);
  const int x1 = std::min(window.x + window.w, w), y1 = std::min(window.y + window.h, h);
  RenderedView out;
  out.image = io::GrayImage(w, h);
  out.shadow_mask = io::GrayImage(w, h);
  if (x1 <= x0 || y1 <= y0) return out;
  const ViewRenderer r(scene, cam);

  // Labels at pixel corners: a pixel whose four corners disagree is crossed by
  // an edge. Its neighbours are refined too, which catches a polygon corner
  // that pokes into a pixel without reaching its corners. The corner grid
  // covers the window and one pixel around it.
  const int gx0 = std::max(x0 - 1, 0), gy0 = std::max(y0 - 1, 0);
  const int gx1 = std::min(x1 + 1, w), gy1 = std::min(y1 + 1, h);  // pixels [g0, g1)
  const int gw = gx1 - gx0 + 1;                                    // corners per row
  std::vector<int> corner(static_cast<std::size_t>(gw) * (gy1 - gy0 + 1));
  for (int j = gy0; j <= gy1; ++j)
    for (int i = gx0; i <= gx1; ++i)
      corner[static_cast<std::size_t>(j - gy0) * gw + (i - gx0)] = r.label(i - 0.5, j - 0.5);
  auto c = [&](int i, int j) { return corner[static_cast<std::size_t>(j - gy0) * gw + (i - gx0)]; };
  auto crossed = [&](int i, int j) {
    const int l = c(i, j);
    return c(i + 1, j) != l || c(i, j + 1) != l || c(i + 1, j + 1) != l;
  };

  const std::uint64_t noise_key =
      mix64(scene.options.seed ^ ((eye == Eye::left ? kStreamNoiseLeft : kStreamNoiseRight) << 56));
  const double sigma = scene.options.noise_sigma_dn;
  const int n_edge = scene.options.edge_supersampling;
  const Response response(scene, cam, eye);
  for (int j = y0; j < y1; ++j)
    for (int i = x0; i < x1; ++i) {
      bool refine = false;
      for (int dj = -1; dj <= 1 && !refine; ++dj)
        for (int di = -1; di <= 1 && !refine; ++di) {
          const int x = i + di, y = j + dj;
          refine = x >= gx0 && y >= gy0 && x < gx1 && y < gy1 && crossed(x, y);
        }
      double mean = 0, shadow_fraction = 0;
      r.integrate(i, j, refine ? n_edge : 2, mean, shadow_fraction);
      out.edge_pixels += refine ? 1 : 0;
      const std::size_t k = static_cast<std::size_t>(j) * w + i;
      double dn = scene.gain_dn * mean;
      if (response.active) dn = response.signal(dn, i, j, k);
      // Read noise plus photon noise: sigma is the value at 128 DN.
      const double s = sigma * std::sqrt(0.25 + 0.75 * std::max(dn, 0.0) / 128.0);
      double value = dn + s * hashed_normal(noise_key, k);
      if (response.active) value = response.gain * value + response.offset;
      out.image.pixels[k] = quantise(value);
      out.shadow_mask.pixels[k] = shadow_fraction > 0.5 ? 255 : 0;
    }
  return out;
}

}  // namespace petra::sim
