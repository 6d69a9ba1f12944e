#include "sim/scene/truth_pixels.hpp"

#include <algorithm>
#include <vector>

#include "sim/scene/camera_rays.hpp"
#include "sim/scene/ray_cast.hpp"

namespace petra::sim {

namespace {

int surface_at(const Scene& s, const CameraRays& rays, double u, double v) {
  return trace(s, rays.origin(), rays.direction(u, v)).surface;
}

// Largest rectangle of true cells in a w x h mask (row-major): histogram of
// runs per column and a stack per row.
Rect largest_rectangle(const std::vector<char>& mask, int w, int h) {
  std::vector<int> run(static_cast<std::size_t>(w) + 1, 0);
  std::vector<int> stack;
  Rect best{0, 0, 0, 0};
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) run[x] = mask[static_cast<std::size_t>(y) * w + x] ? run[x] + 1 : 0;
    stack.clear();
    for (int x = 0; x <= w; ++x) {
      const int height = x < w ? run[x] : 0;
      while (!stack.empty() && run[stack.back()] >= height) {
        const int top = run[stack.back()];
        stack.pop_back();
        const int left = stack.empty() ? 0 : stack.back() + 1;
        if (static_cast<long>(top) * (x - left) > static_cast<long>(best.w) * best.h)
          best = {left, y - top + 1, x - left, top};
      }
      stack.push_back(x);
    }
  }
  return best;
}

// The pixel of a non-empty list nearest their centroid.
Eigen::Vector2i nearest_to_centroid(const std::vector<Eigen::Vector2i>& pixels) {
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const auto& p : pixels) mean += p.cast<double>();
  mean /= static_cast<double>(pixels.size());
  return *std::min_element(pixels.begin(), pixels.end(), [&](const auto& a, const auto& b) {
    return (a.template cast<double>() - mean).squaredNorm() <
           (b.template cast<double>() - mean).squaredNorm();
  });
}

}  // namespace

Rect roi_inside_rock(const Scene& s, const Rect& a) {
  const CameraRays rays(s.rig.left);
  // Corner (i, j) of the grid is the pixel corner (a.x + i - 0.5, a.y + j - 0.5).
  std::vector<char> corner(static_cast<std::size_t>(a.w + 1) * (a.h + 1));
  for (int j = 0; j <= a.h; ++j)
    for (int i = 0; i <= a.w; ++i)
      corner[static_cast<std::size_t>(j) * (a.w + 1) + i] =
          is_target_face(surface_at(s, rays, a.x + i - 0.5, a.y + j - 0.5));
  std::vector<char> mask(static_cast<std::size_t>(a.w) * a.h);
  for (int j = 0; j < a.h; ++j)
    for (int i = 0; i < a.w; ++i) {
      auto c = [&](int di, int dj) {
        return corner[static_cast<std::size_t>(j + dj) * (a.w + 1) + i + di] != 0;
      };
      mask[static_cast<std::size_t>(j) * a.w + i] =
          c(0, 0) && c(1, 0) && c(0, 1) && c(1, 1) &&
          is_target_face(surface_at(s, rays, a.x + i, a.y + j));
    }
  Rect r = largest_rectangle(mask, a.w, a.h);
  // One pixel less all round: a rough face's outline can dip between samples.
  if (r.w <= 2 || r.h <= 2) return {a.x, a.y, 0, 0};
  return {a.x + r.x + 1, a.y + r.y + 1, r.w - 2, r.h - 2};
}

std::optional<Eigen::Vector2i> click_on_rock(const Scene& s, const Rect& roi,
                                             const std::vector<VisibleFacet>& facets, int rock) {
  const CameraRays rays(s.rig.left);
  // Sunlit pixels per rock face.
  std::vector<std::vector<Eigen::Vector2i>> lit(rock_at(s, rock).faces.size());
  for (int v = roi.y; v < roi.y + roi.h; v += 2)
    for (int u = roi.x; u < roi.x + roi.w; u += 2) {
      const SceneHit hit = trace(s, rays.origin(), rays.direction(u, v));
      const int face = face_of_rock(hit.surface, rock);
      if (face >= 0 && !in_shadow(s, hit)) lit[static_cast<std::size_t>(face)].emplace_back(u, v);
    }
  // A well-lit facet first (a face lit at grazing incidence looks like shadow).
  const std::vector<Eigen::Vector2i>* chosen = nullptr;
  for (const double min_sun : {kMinClickSunCosine, 0.0})
    for (const auto& f : facets)
      if (!chosen && lit[static_cast<std::size_t>(f.face)].size() >= kMinClickPixels &&
          f.normal.dot(s.sun_dir) >= min_sun)
        chosen = &lit[static_cast<std::size_t>(f.face)];
  if (!chosen) return std::nullopt;
  return nearest_to_centroid(*chosen);
}

std::optional<Eigen::Vector2i> pixel_on_rock(const Scene& s, const Rect& roi, int rock) {
  const CameraRays rays(s.rig.left);
  std::vector<Eigen::Vector2i> seen;
  for (int v = roi.y; v < roi.y + roi.h; v += 2)
    for (int u = roi.x; u < roi.x + roi.w; u += 2)
      if (face_of_rock(trace(s, rays.origin(), rays.direction(u, v)).surface, rock) >= 0)
        seen.emplace_back(u, v);
  if (seen.empty()) return std::nullopt;
  return nearest_to_centroid(seen);
}

}  // namespace petra::sim
