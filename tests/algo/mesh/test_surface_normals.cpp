#include "algo/mesh/surface_normals.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "tests/support/heap_counter.hpp"
#include "tests/support/synthetic_disparity.hpp"
#include "tests/support/test_rig.hpp"

namespace petra {
namespace {

double angle_deg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b)) * 180 / M_PI;
}

struct NormalsScene {
  StereoRig rig = test::looking_rig(4);
  RectifiedPair pair = *rectify_geometry(rig, 1024, 768);
  test::Rock rock = test::ridge_rock();
  test::SyntheticDisparity disp;
  std::vector<Eigen::Vector3d> normals;
};

TEST(SurfaceNormals, FacesOfARidgeRockAndTheGround) {
  NormalsScene s;
  const Rect roi = test::rock_box(s.pair, s.rock, 40, 30, 55, 20);
  s.disp = test::render_disparity(s.pair, roi, s.rock, 0.05, 2);
  s.normals.resize(s.disp.q4.size());
  std::vector<std::byte> block(surface_normals_scratch_bytes(roi.w));
  Arena arena(block);
  test::HeapScope scope;
  ASSERT_TRUE(surface_normals(s.disp.view(), s.pair.left, NormalParams{}, s.normals, arena).ok());
  EXPECT_EQ(scope.allocations(), 0u);
  // Away from creases (every pixel of the 9 x 9 box on one surface), the
  // fitted normal is the surface's within a degree.
  int checked = 0;
  double worst = 0;
  std::vector<double> errors;
  for (int y = 4; y < roi.h - 4; ++y)
    for (int x = 4; x < roi.w - 4; ++x) {
      const int surface = s.disp.surface[static_cast<std::size_t>(y) * roi.w + x];
      bool uniform = surface >= -1;
      for (int dy = -4; dy <= 4 && uniform; ++dy)
        for (int dx = -4; dx <= 4 && uniform; ++dx)
          uniform = s.disp.surface[static_cast<std::size_t>(y + dy) * roi.w + x + dx] == surface;
      if (!uniform) continue;
      const Eigen::Vector3d truth = surface < 0 ? Eigen::Vector3d::UnitZ()
                                                : s.rock.faces[static_cast<std::size_t>(surface)].n;
      const double e = angle_deg(s.normals[static_cast<std::size_t>(y) * roi.w + x], truth);
      worst = std::max(worst, e);
      errors.push_back(e);
      ++checked;
    }
  EXPECT_GT(checked, 5000);
  std::sort(errors.begin(), errors.end());
  // 0.05 px disparity noise over a 9 x 9 box.
  EXPECT_LT(errors[errors.size() / 2], 0.5);
  EXPECT_LT(worst, 3.0);
}

TEST(SurfaceNormals, SparseBoxesGiveNoNormalAndBadInputIsNamed) {
  NormalsScene s;
  const Rect roi = test::rock_box(s.pair, s.rock, 40, 30, 55, 20);
  s.disp = test::render_disparity(s.pair, roi, s.rock);
  // Keep one pixel in 20: no box is half full.
  for (std::size_t i = 0; i < s.disp.q4.size(); ++i)
    if (i % 20 != 0) s.disp.q4[i] = kInvalidDisparity;
  s.normals.resize(s.disp.q4.size());
  StaticArena<1 << 16> arena;
  ASSERT_TRUE(
      surface_normals(s.disp.view(), s.pair.left, NormalParams{}, s.normals, arena.arena()).ok());
  for (const auto& n : s.normals) EXPECT_EQ(n.squaredNorm(), 0.0);
  NormalParams p;
  p.window = 8;
  EXPECT_EQ(surface_normals(s.disp.view(), s.pair.left, p, s.normals, arena.arena()).code(),
            Errc::invalid_argument);
  std::vector<Eigen::Vector3d> small(10);
  EXPECT_EQ(
      surface_normals(s.disp.view(), s.pair.left, NormalParams{}, small, arena.arena()).code(),
      Errc::invalid_argument);
}

// On a pixel stride (the reconstruction's points above its budget) the
// normals on the stride grid, packed, are bit for bit those of stride 1.
TEST(SurfaceNormals, OnAStrideTheGridPixelsMatchStrideOne) {
  NormalsScene s;
  const Rect roi = test::rock_box(s.pair, s.rock, 40, 30, 55, 20);
  s.disp = test::render_disparity(s.pair, roi, s.rock, 0.05, 2);
  s.normals.resize(s.disp.q4.size());
  const int stride = 3, packed_w = (roi.w + stride - 1) / stride;
  const int packed_h = (roi.h + stride - 1) / stride;
  std::vector<Eigen::Vector3d> packed(static_cast<std::size_t>(packed_w) * packed_h);
  StaticArena<1 << 16> arena;
  ASSERT_TRUE(
      surface_normals(s.disp.view(), s.pair.left, NormalParams{}, s.normals, arena.arena()).ok());
  ASSERT_TRUE(
      surface_normals(s.disp.view(), s.pair.left, NormalParams{}, packed, arena.arena(), stride)
          .ok());
  int nonzero = 0;
  for (int y = 0; y < roi.h; y += stride)
    for (int x = 0; x < roi.w; x += stride) {
      const Eigen::Vector3d& full = s.normals[static_cast<std::size_t>(y) * roi.w + x];
      EXPECT_EQ(packed[static_cast<std::size_t>(y / stride) * packed_w + x / stride], full)
          << x << "," << y;
      nonzero += full.squaredNorm() > 0;
    }
  EXPECT_GT(nonzero, 500);
  packed.pop_back();  // one short of the packed grid
  EXPECT_EQ(
      surface_normals(s.disp.view(), s.pair.left, NormalParams{}, packed, arena.arena(), stride)
          .code(),
      Errc::invalid_argument);
  EXPECT_EQ(surface_normals(s.disp.view(), s.pair.left, NormalParams{}, s.normals, arena.arena(), 0)
                .code(),
            Errc::invalid_argument);
}

}  // namespace
}  // namespace petra
