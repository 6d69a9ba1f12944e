#include "algo/camera/rectify.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "tests/support/heap_counter.hpp"

namespace petra {
namespace {

// A Bumblebee2-like rig (150 mm baseline, 4.65 um pixels, 3.8 mm lens),
// slightly converged and misaligned, with radial distortion.
StereoRig test_rig(int w = 640, int h = 480) {
  StereoRig rig;
  for (int k = 0; k < 2; ++k) {
    TsaiCamera& c = k == 0 ? rig.left : rig.right;
    c.width = w;
    c.height = h;
    c.f_mm = k == 0 ? 3.80 : 3.82;
    c.dx_mm = c.dy_mm = 0.00465 * 1024.0 / w;
    c.sx = 1.0;
    c.cx_px = (w - 1) / 2.0 + (k == 0 ? 4.0 : -3.0);
    c.cy_px = (h - 1) / 2.0 + (k == 0 ? -2.0 : 2.5);
    c.kappa1 = k == 0 ? 0.02 : 0.015;
    c.R = (Eigen::AngleAxisd(k == 0 ? 0.01 : -0.01, Eigen::Vector3d::UnitY()) *
           Eigen::AngleAxisd(k == 0 ? 0.004 : -0.002, Eigen::Vector3d::UnitX()))
              .toRotationMatrix();
    const Eigen::Vector3d centre(k == 0 ? -75.0 : 75.0, k == 0 ? 0.0 : 1.0, 0.0);
    c.T_mm = -(c.R * centre);
  }
  return rig;
}

struct Tables {
  std::vector<RemapEntry> l, r;
  explicit Tables(const StereoRig& rig)
      : l(Rectifier::table_entries(rig.left.width, rig.left.height)), r(l.size()) {}
};

TEST(Rectify, TablesReproduceTheExactModelWithinAThirtySecondOfAPixel) {
  // Bilinear interpolation of a linear image is exact, so the rectified gray
  // value tells where the table sampled: compare with the double-precision map.
  const StereoRig rig = test_rig();
  Tables t(rig);
  auto rect = Rectifier::create(rig, t.l, t.r);
  ASSERT_TRUE(rect.ok()) << rect.error().message;
  const int w = rig.left.width, h = rig.left.height;
  const double a = 0.3, b = 0.12;  // gray per px along x and y
  std::vector<std::uint8_t> orig(static_cast<std::size_t>(w) * h), out(orig.size());
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      orig[static_cast<std::size_t>(y) * w + x] =
          static_cast<std::uint8_t>(a * x * 0.5 + b * y * 0.5 + 20);
  for (StereoSide side : {StereoSide::left, StereoSide::right}) {
    ASSERT_TRUE(
        rect->rectify(side, ConstGray8View(orig.data(), w, h), Gray8View(out.data(), w, h)).ok());
    int checked = 0;
    for (int v = 0; v < h; v += 7)
      for (int u = 0; u < w; u += 7) {
        auto src = rect->to_original(side, {u, v});
        ASSERT_TRUE(src.ok());
        if (src->x() < 1 || src->y() < 1 || src->x() > w - 2 || src->y() > h - 2) continue;
        // The stored image is truncated to integers, so compare with the
        // bilinear interpolation of the stored values at the exact position.
        const int x0 = static_cast<int>(std::floor(src->x())),
                  y0 = static_cast<int>(std::floor(src->y()));
        const double fx = src->x() - x0, fy = src->y() - y0;
        auto px = [&](int x, int y) {
          return static_cast<double>(orig[static_cast<std::size_t>(y) * w + x]);
        };
        const double expect = (1 - fy) * ((1 - fx) * px(x0, y0) + fx * px(x0 + 1, y0)) +
                              fy * ((1 - fx) * px(x0, y0 + 1) + fx * px(x0 + 1, y0 + 1));
        // 1/32 px of position error times a gradient < 1 gray/px, plus rounding.
        EXPECT_NEAR(out[static_cast<std::size_t>(v) * w + u], expect, 1.0) << u << "," << v;
        ++checked;
      }
    EXPECT_GT(checked, 4000);
  }
}

TEST(Rectify, CorrespondencesShareARowAndTriangulateBack) {
  const StereoRig rig = test_rig();
  Tables t(rig);
  auto rect = Rectifier::create(rig, t.l, t.r);
  ASSERT_TRUE(rect.ok());
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i < 200; ++i) {
    const Eigen::Vector3d pw(150 * u(rng), 100 * u(rng), 800 + 300 * u(rng));
    auto ol = project(rig.left, pw);
    auto orr = project(rig.right, pw);
    ASSERT_TRUE(ol.ok() && orr.ok());
    auto rl = rect->to_rectified(StereoSide::left, *ol);
    auto rr = rect->to_rectified(StereoSide::right, *orr);
    ASSERT_TRUE(rl.ok() && rr.ok());
    EXPECT_NEAR(rl->y(), rr->y(), 1e-6);
    const double d = rl->x() - rr->x();
    auto p = rect->point_3d(rl->x(), rl->y(), d);
    ASSERT_TRUE(p.ok());
    EXPECT_LT((*p - pw).norm(), 1e-6);
    auto back = rect->to_original(StereoSide::left, *rl);  // round trip through distortion
    ASSERT_TRUE(back.ok());
    EXPECT_LT((*back - *ol).norm(), 1e-6);
  }
}

TEST(Rectify, AnAlreadyRectifiedRigMapsEveryPixelToItself) {
  StereoRig rig = test_rig(320, 240);
  for (TsaiCamera* c : {&rig.left, &rig.right}) {
    c->f_mm = 3.8;
    c->kappa1 = 0.0;
    c->cx_px = 159.5;
    c->cy_px = 119.5;
    c->R = Eigen::Matrix3d::Identity();
  }
  rig.left.T_mm = Eigen::Vector3d(75, 0, 0);
  rig.right.T_mm = Eigen::Vector3d(-75, 0, 0);
  Tables t(rig);
  auto rect = Rectifier::create(rig, t.l, t.r);
  ASSERT_TRUE(rect.ok());
  std::vector<std::uint8_t> img(320 * 240), out(img.size());
  std::mt19937 rng(1);
  for (auto& v : img) v = static_cast<std::uint8_t>(rng());
  ASSERT_TRUE(rect->rectify(StereoSide::right, ConstGray8View(img.data(), 320, 240),
                            Gray8View(out.data(), 320, 240))
                  .ok());
  EXPECT_EQ(img, out);
}

TEST(Rectify, RegionWritesOnlyTheRegion) {
  const StereoRig rig = test_rig(160, 120);
  Tables t(rig);
  auto rect = Rectifier::create(rig, t.l, t.r);
  ASSERT_TRUE(rect.ok());
  std::vector<std::uint8_t> img(160 * 120, 200), out(img.size(), 7);
  const Rect region{40, 30, 50, 20};
  ASSERT_TRUE(rect->rectify(StereoSide::left, ConstGray8View(img.data(), 160, 120),
                            Gray8View(out.data(), 160, 120), region)
                  .ok());
  for (int y = 0; y < 120; ++y)
    for (int x = 0; x < 160; ++x) {
      const std::uint8_t v = out[static_cast<std::size_t>(y) * 160 + x];
      if (region.contains(x, y))
        EXPECT_EQ(v, 200);
      else
        EXPECT_EQ(v, 7);
    }
}

// A drifted pair's right view rectified with its rows moved (the
// calibration check's correction): a whole row equals the plain view one row
// further down; half a row is the two rows' mean on a smooth image; rows whose
// source row is outside the table are filled; zero changes nothing.
TEST(Rectify, RowsMovedSampleTheTableRowsThatFar) {
  const int w = 160, h = 120;
  const StereoRig rig = test_rig(w, h);
  Tables t(rig);
  auto rect = Rectifier::create(rig, t.l, t.r);
  ASSERT_TRUE(rect.ok());
  std::vector<std::uint8_t> img(static_cast<std::size_t>(w) * h);  // smooth: sampling commutes
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      img[static_cast<std::size_t>(y) * w + x] =
          static_cast<std::uint8_t>(128 + 100 * std::sin(x / 7.0) * std::cos(y / 9.0));
  const ConstGray8View src(img.data(), w, h);
  const Rect all{0, 0, w, h};
  auto rectified = [&](int rows_q4) {
    std::vector<std::uint8_t> out(img.size(), 7);
    EXPECT_TRUE(
        rect->rectify_rows_moved(StereoSide::right, src, Gray8View(out.data(), w, h), all, rows_q4)
            .ok());
    return out;
  };
  std::vector<std::uint8_t> plain(img.size());
  ASSERT_TRUE(rect->rectify(StereoSide::right, src, Gray8View(plain.data(), w, h), all).ok());
  EXPECT_EQ(rectified(0), plain);
  const auto up = rectified(16), half = rectified(8), down = rectified(-16);
  auto at = [w](const std::vector<std::uint8_t>& v, int x, int y) {
    return static_cast<int>(v[static_cast<std::size_t>(y) * w + x]);
  };
  int between = 0, inside = 0;
  for (int y = 1; y < h - 1; ++y)
    for (int x = 0; x < w; ++x) {
      EXPECT_EQ(at(up, x, y), at(plain, x, y + 1));
      EXPECT_EQ(at(down, x, y), at(plain, x, y - 1));
      const int mid = at(plain, x, y) + at(plain, x, y + 1);  // twice the two rows' mean
      between += std::abs(2 * at(half, x, y) - mid) <= 4;
      ++inside;
    }
  EXPECT_GT(between, inside * 99 / 100);
  for (int x = 0; x < w; ++x) {
    EXPECT_EQ(at(up, x, h - 1), kRectifyFill);
    EXPECT_EQ(at(down, x, 0), kRectifyFill);
  }
}

TEST(Rectify, RoiMapsToABoxHoldingItsOutline) {
  const StereoRig rig = test_rig();
  Tables t(rig);
  auto rect = Rectifier::create(rig, t.l, t.r);
  ASSERT_TRUE(rect.ok());
  const Rect roi{200, 150, 120, 90};
  auto r = rect->roi_to_rectified(StereoSide::left, roi);
  ASSERT_TRUE(r.ok()) << r.error().message;
  for (int x = roi.x; x < roi.x + roi.w; x += 11)
    for (int y : {roi.y, roi.y + roi.h - 1}) {
      auto p = rect->to_rectified(StereoSide::left, {x, y});
      ASSERT_TRUE(p.ok());
      EXPECT_TRUE(r->contains(static_cast<int>(std::lround(p->x())),
                              static_cast<int>(std::lround(p->y()))));
    }
  EXPECT_NEAR(r->w, roi.w, 6);  // a mild rectification keeps the size
  EXPECT_NEAR(r->h, roi.h, 6);
  auto back = rect->roi_to_original(StereoSide::left, *r);
  ASSERT_TRUE(back.ok());
  EXPECT_LE(back->x, roi.x);
  EXPECT_LE(back->y, roi.y);
  EXPECT_GE(back->x + back->w, roi.x + roi.w);
  EXPECT_GE(back->y + back->h, roi.y + roi.h);
}

TEST(Rectify, BadInputNamesTheProblem) {
  StereoRig rig = test_rig(160, 120);
  Tables t(rig);
  std::vector<RemapEntry> small(10);
  auto a = Rectifier::create(rig, small, t.r);
  EXPECT_EQ(a.code(), Errc::capacity_exceeded);
  EXPECT_NE(std::strstr(a.error().message, "tables need"), nullptr);
  StereoRig odd = rig;
  odd.right.width = 200;
  auto b = Rectifier::create(odd, t.l, t.r);
  EXPECT_EQ(b.code(), Errc::invalid_argument);
  StereoRig same = rig;
  same.right.T_mm = same.left.T_mm;
  same.right.R = same.left.R;
  auto c = Rectifier::create(same, t.l, t.r);
  EXPECT_EQ(c.code(), Errc::degenerate);
  StereoRig bad = rig;
  bad.left.f_mm = -1;
  EXPECT_FALSE(Rectifier::create(bad, t.l, t.r).ok());

  auto rect = Rectifier::create(rig, t.l, t.r);
  ASSERT_TRUE(rect.ok());
  std::vector<std::uint8_t> img(160 * 120), wrong(100 * 100);
  auto d = rect->rectify(StereoSide::left, ConstGray8View(wrong.data(), 100, 100),
                         Gray8View(img.data(), 160, 120));
  EXPECT_EQ(d.code(), Errc::invalid_argument);
  EXPECT_NE(std::strstr(d.error().message, "original image is 100x100"), nullptr)
      << d.error().message;
  auto e = rect->rectify(StereoSide::left, ConstGray8View(img.data(), 160, 120),
                         Gray8View(img.data(), 160, 120), Rect{150, 0, 20, 10});
  EXPECT_EQ(e.code(), Errc::out_of_range);
  EXPECT_EQ(rect->roi_to_rectified(StereoSide::left, Rect{150, 100, 20, 30}).code(),
            Errc::out_of_range);
  EXPECT_EQ(rect->roi_to_rectified(StereoSide::left, Rect{10, 10, 0, 30}).code(),
            Errc::invalid_argument);
  Rectifier empty;
  EXPECT_EQ(empty
                .rectify(StereoSide::left, ConstGray8View(img.data(), 160, 120),
                         Gray8View(img.data(), 160, 120))
                .code(),
            Errc::not_ready);
}

TEST(Rectify, ApplyingTablesAndMappingPointsAllocateNothing) {
  const StereoRig rig = test_rig(320, 240);
  Tables t(rig);
  auto rect = Rectifier::create(rig, t.l, t.r);
  ASSERT_TRUE(rect.ok());
  std::vector<std::uint8_t> img(320 * 240, 100), out(img.size());
  petra::test::HeapScope scope;
  for (int i = 0; i < 3; ++i) {
    ASSERT_TRUE(rect->rectify(StereoSide::left, ConstGray8View(img.data(), 320, 240),
                              Gray8View(out.data(), 320, 240))
                    .ok());
    ASSERT_TRUE(rect->roi_to_rectified(StereoSide::left, Rect{100, 80, 60, 50}).ok());
    ASSERT_TRUE(rect->point_3d(160, 120, 20).ok());
  }
  EXPECT_EQ(scope.allocations(), 0u);
}

}  // namespace
}  // namespace petra
