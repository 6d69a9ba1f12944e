// Photometric plane refinement (algo/surface/plane_photometric): a steep, weakly
// textured face rendered into both views with a known disparity plane; the
// refinement starts from a plane that leans like a staircase fit does.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "algo/surface/plane_photometric.hpp"
#include "tests/support/heap_counter.hpp"

namespace petra {
namespace {

constexpr int kW = 200, kH = 90;
const DisparityPlane kTruth{-0.21, 0.02, 30.0, 100.0, 45.0};  // steep in u, as scene 11's face

// Weak texture (a few gray levels, like an unlit face under ambient light)
// on the surface, indexed by the left pixel it is seen at.
double texture(double u, double v) {
  return 90 + 3.0 * std::sin(0.9 * u + 0.4 * v) + 2.0 * std::sin(0.37 * u - 0.8 * v + 1.0) +
         1.5 * std::cos(1.7 * u + 1.1 * v);
}

// Deterministic noise of about one gray level.
double noise(int x, int y, int seed) {
  const std::uint32_t h = static_cast<std::uint32_t>(x) * 73856093u ^
                          static_cast<std::uint32_t>(y) * 19349663u ^
                          static_cast<std::uint32_t>(seed) * 83492791u;
  return static_cast<double>((h * 2654435761u) >> 24) / 128.0 - 1.0;
}

struct Pair {
  std::vector<std::uint8_t> left, right;
  Pair() : left(kW * kH), right(kW * kH) {
    for (int v = 0; v < kH; ++v)
      for (int x = 0; x < kW; ++x) {
        left[v * kW + x] = static_cast<std::uint8_t>(std::lround(texture(x, v) + noise(x, v, 1)));
        // Right pixel x sees the left pixel u with u - d(u, v) = x.
        const double u =
            (x + kTruth.c - kTruth.a * kTruth.u0 + kTruth.b * (v - kTruth.v0)) / (1.0 - kTruth.a);
        right[v * kW + x] = static_cast<std::uint8_t>(std::lround(texture(u, v) + noise(x, v, 2)));
      }
  }
  ConstGray8View l() const { return ConstGray8View(left.data(), kW, kH); }
  ConstGray8View r() const { return ConstGray8View(right.data(), kW, kH); }
};

std::vector<PixelPos> face() {
  std::vector<PixelPos> px;
  for (int v = 20; v < 70; ++v)
    for (int u = 75; u < 125; ++u)
      px.push_back({static_cast<std::int16_t>(u), static_cast<std::int16_t>(v)});
  return px;
}

// The worst disparity error over the face (px).
double worst(const DisparityPlane& q) {
  double m = 0;
  for (int u : {75, 124})
    for (int v : {20, 69}) m = std::max(m, std::abs(q.at(u, v) - kTruth.at(u, v)));
  return m;
}

TEST(PlanePhotometric, RecoversASteepWeaklyTexturedFaceFromALeaningStart) {
  const Pair p;
  const std::vector<PixelPos> px = face();
  const Rect all{0, 0, kW, kH};
  // A staircase fit: the slope in u is off by 0.035 px/px (a few degrees of
  // normal at the rock), in v by 0.01, and the offset by 0.3 px.
  DisparityPlane start = kTruth;
  start.a += 0.035;
  start.b -= 0.01;
  start.c += 0.3;
  ASSERT_GT(worst(start), 1.0);
  test::HeapScope scope;
  auto fit = refine_plane_photometric(p.l(), p.r(), all, px, start, {});
  EXPECT_EQ(scope.allocations(), 0u);
  ASSERT_TRUE(fit.ok()) << fit.error().message;
  EXPECT_TRUE(fit->accepted);
  EXPECT_NEAR(fit->plane.a, kTruth.a, 0.004);
  EXPECT_NEAR(fit->plane.b, kTruth.b, 0.004);
  EXPECT_LT(worst(fit->plane), 0.15);
  EXPECT_LT(fit->rms_after, fit->rms_before);
  EXPECT_GT(fit->pixels, static_cast<long>(px.size()) * 3 / 4);  // trimmed at 2 RMS
}

TEST(PlanePhotometric, AGainAndOffsetBetweenTheCamerasDoNotMoveThePlane) {
  Pair p;
  for (std::uint8_t& g : p.right) g = static_cast<std::uint8_t>(std::lround(1.2 * g + 7));
  DisparityPlane start = kTruth;
  start.a += 0.02;
  auto fit = refine_plane_photometric(p.l(), p.r(), Rect{0, 0, kW, kH}, face(), start, {});
  ASSERT_TRUE(fit.ok());
  EXPECT_TRUE(fit->accepted);
  EXPECT_LT(worst(fit->plane), 0.15);
}

TEST(PlanePhotometric, AStartOutsideTheBasinIsRefusedNotFollowed) {
  const Pair p;
  DisparityPlane start = kTruth;
  start.c += 6.0;  // six pixels off: another texture period
  PhotometricPlaneParams params;
  params.max_shift_px = 1.0;
  auto fit = refine_plane_photometric(p.l(), p.r(), Rect{0, 0, kW, kH}, face(), start, params);
  ASSERT_TRUE(fit.ok());
  if (!fit->accepted) {
    EXPECT_EQ(fit->plane.c, start.c);  // the initial plane is returned unchanged
  } else {
    EXPECT_LE(worst(fit->plane) - 0.0, 6.0 + params.max_shift_px);
  }
}

TEST(PlanePhotometric, TooFewPixelsKeepTheInitialPlane) {
  const Pair p;
  std::vector<PixelPos> px = face();
  px.resize(50);
  auto fit = refine_plane_photometric(p.l(), p.r(), Rect{0, 0, kW, kH}, px, kTruth, {});
  ASSERT_TRUE(fit.ok());
  EXPECT_FALSE(fit->accepted);
  EXPECT_EQ(fit->plane.a, kTruth.a);
}

TEST(PlanePhotometric, BadInputIsNamed) {
  const Pair p;
  PhotometricPlaneParams bad;
  bad.trim_sigma = 0.5;
  auto r = refine_plane_photometric(p.l(), p.r(), Rect{0, 0, kW, kH}, face(), kTruth, bad);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(std::string(r.error().message).find("trim_sigma"), std::string::npos);
  std::vector<PixelPos> outside{{static_cast<std::int16_t>(kW + 3), 4}};
  r = refine_plane_photometric(p.l(), p.r(), Rect{0, 0, kW, kH}, outside, kTruth, {});
  ASSERT_FALSE(r.ok());
  EXPECT_NE(std::string(r.error().message).find("outside"), std::string::npos);
  r = refine_plane_photometric(p.l(), p.r(), Rect{0, 0, kW + 1, kH}, face(), kTruth, {});
  ASSERT_FALSE(r.ok());
  EXPECT_NE(std::string(r.error().message).find("right area"), std::string::npos);
}

TEST(PlanePhotometric, FacePixelsLeaveOutTheBorderAndTakeHolesInside) {
  // 12 x 8 class image: class 2 on the left 8 columns, class 3 on the rest,
  // one unknown hole inside class 2.
  constexpr int w = 12, h = 8;
  std::vector<std::uint8_t> c(w * h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) c[y * w + x] = x < 8 ? 2 : 3;
  c[4 * w + 3] = 0xFF;
  const Rect roi{100, 50, w, h};
  std::vector<PixelPos> out(w * h);
  std::vector<std::int32_t> scratch(face_pixels_scratch(w, h));
  const std::size_t n =
      face_pixels(ImageView<const std::uint8_t>(c.data(), w, h), roi, 2, 1, scratch, out);
  // Columns 1..6 (column 7 touches class 3), rows 1..6: 36, the hole included.
  EXPECT_EQ(n, 36u);
  bool hole = false;
  for (std::size_t i = 0; i < n; ++i) {
    EXPECT_GE(out[i].u, 101);
    EXPECT_LE(out[i].u, 106);
    hole |= out[i].u == 103 && out[i].v == 54;
  }
  EXPECT_TRUE(hole);
}

TEST(PlanePhotometric, FacePixelsTakeABandOfNoMatchAcrossTheFace) {
  // 20 x 10 class image, all class 2 but a band of unknown pixels 4 columns
  // wide (a matcher's false occlusion on a steep face) and class 3 on the
  // right 3 columns. The band lies between face pixels on every row: it is
  // on the face.
  constexpr int w = 20, h = 10;
  std::vector<std::uint8_t> c(w * h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) c[y * w + x] = x >= 17 ? 3 : (x >= 6 && x < 10 ? 0xFF : 2);
  const Rect roi{0, 0, w, h};
  std::vector<PixelPos> out(w * h);
  std::vector<std::int32_t> scratch(face_pixels_scratch(w, h));
  const std::size_t n =
      face_pixels(ImageView<const std::uint8_t>(c.data(), w, h), roi, 2, 1, scratch, out);
  int band = 0;
  for (std::size_t i = 0; i < n; ++i) band += out[i].u >= 6 && out[i].u < 10;
  EXPECT_EQ(band, 4 * 8);  // every band pixel of rows 1..8
  EXPECT_EQ(n, 15u * 8u);  // columns 1..15 (16 touches class 3), rows 1..8
  // Too little scratch: nothing, not a write past its end.
  std::vector<std::int32_t> short_scratch(3);
  EXPECT_EQ(
      face_pixels(ImageView<const std::uint8_t>(c.data(), w, h), roi, 2, 1, short_scratch, out),
      0u);
}

TEST(PlanePhotometric, ABlurrierRightViewDoesNotTiltThePlane) {
  // A face seen more obliquely by the right camera: each right pixel
  // integrates more of the surface, so the right image is the blurrier.
  // Rendered here by averaging the texture over a right pixel's footprint
  // (5 samples across it), a face with fine detail. Without a blur term the
  // fit trades the slope against the lost detail (the residual's second
  // derivative of the texture correlates with the slope's Jacobian through
  // the face's ends).
  const DisparityPlane truth{0.28, 0.0, 30.0, 100.0, 45.0};  // compressed in the right view
  const auto fine = [](double u, double v) {
    return 100 + 14.0 * std::sin(1.4 * u + 0.3 * v) + 10.0 * std::sin(0.9 * u - 0.9 * v + 2.0) +
           6.0 * std::sin(0.45 * u + 0.7 * v + 1.0);
  };
  std::vector<std::uint8_t> left(kW * kH), right(kW * kH);
  for (int v = 0; v < kH; ++v)
    for (int x = 0; x < kW; ++x) {
      left[v * kW + x] = static_cast<std::uint8_t>(std::lround(fine(x, v) + noise(x, v, 1)));
      // Right pixel [x - 1/2, x + 1/2] sees left [u(x - 1/2), u(x + 1/2)], wider by 1 / (1 - a).
      double sum = 0;
      for (int k = 0; k < 5; ++k) {
        const double xs = x - 0.4 + 0.2 * k;
        const double u =
            (xs + truth.c - truth.a * truth.u0 + truth.b * (v - truth.v0)) / (1.0 - truth.a);
        sum += fine(u, v);
      }
      right[v * kW + x] = static_cast<std::uint8_t>(std::lround(0.2 * sum + noise(x, v, 2)));
    }
  // The left pixel averages its own footprint too (5 samples across it).
  for (int v = 0; v < kH; ++v)
    for (int x = 0; x < kW; ++x) {
      double sum = 0;
      for (int k = 0; k < 5; ++k) sum += fine(x - 0.4 + 0.2 * k, v);
      left[v * kW + x] = static_cast<std::uint8_t>(std::lround(0.2 * sum + noise(x, v, 1)));
    }
  const ConstGray8View l(left.data(), kW, kH), r(right.data(), kW, kH);
  DisparityPlane start = truth;
  start.a += 0.02;
  start.c += 0.3;
  const std::vector<PixelPos> px = face();
  test::HeapScope scope;
  auto fit = refine_plane_photometric(l, r, Rect{0, 0, kW, kH}, px, start, {});
  EXPECT_EQ(scope.allocations(), 0u);
  ASSERT_TRUE(fit.ok());
  EXPECT_TRUE(fit->accepted);
  std::printf("blurrier right view: a %.4f (truth %.4f), b %.4f (truth %.4f)\n", fit->plane.a,
              truth.a, fit->plane.b, truth.b);
  EXPECT_NEAR(fit->plane.a, truth.a, 0.0006);  // without the blur term: 0.0013 off
  EXPECT_NEAR(fit->plane.b, truth.b, 0.002);
}

}  // namespace
}  // namespace petra
