// The plane uncertainty counts a face's pixels: a triangle stands for the
// pixels it covers, what it shows the camera, however the matcher tilted it.
#include "algo/surface/grind_qualify.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <span>
#include <vector>

namespace petra {
namespace {

constexpr double kViewDeg = 65.0;
constexpr double kFocalPx = 1000.0;
constexpr double kBaselineMm = 100.0;

// A face seen at 65 deg about 900 mm away, meshed on the pixel grid (81 x 81
// pixels about the principal point, each cell two triangles) as a matcher
// of whole-pixel disparity lays it out: fronto-parallel treads, the risers
// between them removed as the mesh filter removes triangles seen edge-on.
// The treads' own area is about cos 65 deg of the face's they cover.
struct TreadFace {
  Eigen::Vector3d camera = Eigen::Vector3d::Zero(), centre{0, 0, 900}, normal;
  std::vector<Eigen::Vector3d> xyz;
  std::vector<FaceSample> samples;
};

TreadFace make_tread_face() {
  TreadFace f;
  const double view = kViewDeg * M_PI / 180.0, fb = kFocalPx * kBaselineMm;
  f.normal = Eigen::Vector3d(0, -std::sin(view), -std::cos(view));  // towards the camera
  constexpr int kHalf = 40;
  std::vector<int> step;
  for (int v = -kHalf; v <= kHalf; ++v)
    for (int u = -kHalf; u <= kHalf; ++u) {
      const Eigen::Vector3d ray(u / kFocalPx, v / kFocalPx, 1.0);
      const double z = f.normal.dot(f.centre) / f.normal.dot(ray);
      const int d = static_cast<int>(std::floor(fb / z));  // whole pixels
      f.xyz.push_back(ray * (fb / d));
      step.push_back(d);
    }
  constexpr int kW = 2 * kHalf + 1;
  auto add = [&](int a, int b, int c) {
    const auto at = [&](int i) { return step[static_cast<std::size_t>(i)]; };
    if (at(a) != at(b) || at(a) != at(c)) return;  // a riser
    MeshTriangle t;
    t.v[0] = a, t.v[1] = b, t.v[2] = c;
    f.samples.push_back(triangle_sample(f.xyz, t, f.camera));
  };
  for (int v = 0; v + 1 < kW; ++v)
    for (int u = 0; u + 1 < kW; ++u) {
      const int i = v * kW + u;
      add(i, i + 1, i + kW + 1);
      add(i, i + kW + 1, i + kW);
    }
  return f;
}

GrindPlane qualified(const TreadFace& f, std::span<const FaceSample> samples) {
  GrindPlane plane;
  plane.normal = f.normal;
  plane.centroid_mm = f.centre;
  std::vector<std::byte> block(footprint_scratch_bytes(samples.size()));
  Arena arena(block);
  const DepthNoise noise{kFocalPx, kBaselineMm, 0.3, 1.0};
  GrindParams params;
  params.max_footprint_rms_mm = 5;  // the treads lie about 2 mm either side of the face
  EXPECT_TRUE(qualify_plane(samples, samples.size(), f.camera, params, noise, arena, plane).ok());
  return plane;
}

TEST(GrindQualify, ATrianglesSeenAreaIsThePixelsItCovers) {
  const TreadFace f = make_tread_face();
  ASSERT_GT(f.samples.size(), 9000u);  // of 12,800: the risers take about a quarter
  double own = 0, seen = 0;
  for (const FaceSample& s : f.samples) {
    const double pixel = (s.p - f.camera).squaredNorm() / (kFocalPx * kFocalPx);
    EXPECT_NEAR(static_cast<double>(s.seen) / pixel, 0.5, 0.02);  // half a pixel cell each
    own += static_cast<double>(s.area);
    seen += static_cast<double>(s.seen);
  }
  EXPECT_NEAR(own / seen, 1.0, 0.02);  // the treads face the camera
}

TEST(GrindQualify, ATreadFaceCountsItsPixelsNotItsTreadsArea) {
  const TreadFace f = make_tread_face();
  const GrindPlane by_pixels = qualified(f, f.samples);
  std::vector<FaceSample> own_area = f.samples;  // as if the camera's view were not known
  for (FaceSample& s : own_area) s.seen = 0;
  const GrindPlane by_area = qualified(f, own_area);
  ASSERT_GT(by_pixels.normal_sigma_deg, 0);
  // Counted by their own area on the face the treads stand for cos 65 deg of
  // their pixels: the normal's 1-sigma would be 1 / sqrt(cos 65 deg) larger.
  EXPECT_NEAR(by_pixels.normal_sigma_deg / by_area.normal_sigma_deg,
              std::sqrt(std::cos(kViewDeg * M_PI / 180.0)), 0.05);
}

}  // namespace
}  // namespace petra
