// Rock detection's back half (algo/propose/rock_detection) on the exact
// disparity of a ray-cast scene at the detection's 1/4 resolution: flat
// ground, ridge rocks at known places. Each rock is found once, with its
// height and size, an ROI holding it and a click on it; the bare ground gives
// no rock (an empty result, not an error).
#include <gtest/gtest.h>

#include <cstdint>
#include <span>
#include <vector>

#include "algo/camera/rectify.hpp"
#include "algo/propose/rock_detection.hpp"
#include "tests/support/synthetic_disparity.hpp"
#include "tests/support/test_rig.hpp"

namespace petra {
namespace {

constexpr int kFactor = 4;

struct Placed {
  test::Rock rock;
  Eigen::Vector3d at;  // where its footprint's centre stands
};

test::Rock moved(test::Rock r, const Eigen::Vector3d& t) {
  for (test::HalfSpace& h : r.faces) h.d -= h.n.dot(t);
  return r;
}

struct Scene {
  StereoRig rig;
  std::vector<RemapEntry> tables[2];
  Rectifier rectifier;
  std::vector<std::int16_t> q4;
  Rect grid;
  ConstDisparityMap map() const {
    return {ImageView<const std::int16_t>(q4.data(), grid.w, grid.h), grid};
  }
};

// The exact disparity of the scene on the 1/4 grid: grid pixel x stands for
// rectified x 4 + 1.5 (algo/mesh/triangulate's factor), its disparity is / 4;
// where rocks overlap, the nearest surface (largest disparity) wins.
void render(Scene& s, const std::vector<test::Rock>& rocks) {
  const RectifiedPair& pair = s.rectifier.geometry();
  test::PinholeView view = test::rectified_view(pair.left);
  view.f_px /= kFactor;
  view.cx = (view.cx - 1.5) / kFactor;
  view.cy = (view.cy - 1.5) / kFactor;
  s.grid = {0, 0, 1024 / kFactor, 768 / kFactor};
  s.q4.assign(static_cast<std::size_t>(s.grid.w) * s.grid.h, kInvalidDisparity);
  std::vector<test::Rock> all = rocks;
  if (all.empty())
    all.push_back(moved(test::ridge_rock(), {0, -3000, 0}));  // behind the cameras: ground only
  for (const test::Rock& r : all) {
    const test::Cloud cloud = test::render(view, s.grid, r);
    for (std::size_t i = 0; i < cloud.xyz.size(); ++i) {
      auto p = rectified_project(pair, cloud.xyz[i]);
      if (!p) continue;
      std::int16_t& q = s.q4[static_cast<std::size_t>(cloud.px[i].v) * s.grid.w + cloud.px[i].u];
      const std::int16_t d = disparity_q4(p->disparity / kFactor);
      if (!is_valid_disparity(q) || d > q) q = d;
    }
  }
}

Scene make_scene(const std::vector<test::Rock>& rocks) {
  Scene s;
  s.rig = test::looking_rig(7);
  for (auto& t : s.tables) t.resize(Rectifier::table_entries(1024, 768));
  s.rectifier = *Rectifier::create(s.rig, s.tables[0], s.tables[1]);
  render(s, rocks);
  return s;
}

Result<DetectionResult> detect(const Scene& s, std::vector<std::byte>& block,
                               std::span<std::uint8_t> rock_map = {}) {
  DetectionBudget b;
  b.factor = kFactor;
  block.assign(detection_arena_bytes(b), std::byte{0});
  Arena arena(block);
  return detect_rocks_in_disparity(s.rectifier, s.map(), b, DetectionParams{}, arena, rock_map);
}

// The candidate whose click lies on the rock placed at `at` (its 3-D point
// within the footprint), or nullptr.
const RockCandidate* found(const Scene& s, const DetectionResult& d, const Eigen::Vector3d& at) {
  auto px = project(s.rig.left, at + Eigen::Vector3d(0, 0, 30));
  if (!px) return nullptr;
  for (int i = 0; i < d.count; ++i)
    if (d.rocks[i].roi.contains(static_cast<int>(px->x()), static_cast<int>(px->y())))
      return &d.rocks[i];
  return nullptr;
}

TEST(RockDetection, FindsEachRidgeRockOnFlatGround) {
  const Eigen::Vector3d a(-120, 0, 0), b(150, 80, 0);
  const Scene s = make_scene({moved(test::ridge_rock(), a), moved(test::ridge_rock(), b)});
  std::vector<std::byte> block;
  auto d = detect(s, block);
  ASSERT_TRUE(d.ok()) << d.error().message;
  EXPECT_EQ(d->count, 2);
  EXPECT_LT(std::acos(std::abs(d->ground.plane.normal.z())) * 180 / M_PI, 0.5);
  for (const Eigen::Vector3d& at : {a, b}) {
    const RockCandidate* k = found(s, *d, at);
    ASSERT_NE(k, nullptr) << "no candidate holds the rock at x = " << at.x();
    EXPECT_NEAR(k->height_mm, 55.0, 4.0);  // the ridge, less a grid pixel's reach
    EXPECT_GT(k->size_mm, 80.0 * 0.9);     // the 80 x 60 footprint's long side or more
    EXPECT_LT(k->size_mm, 100.0 * 1.15);   // ... its diagonal at most
    EXPECT_TRUE(k->roi.contains(k->click_u, k->click_v));
    EXPECT_TRUE(k->roi.inside(1024, 768));
  }
}

TEST(RockDetection, SplitsTwoTouchingRocksAtTheSaddle) {
  // Wall to wall along x: one region standing out of the ground, two ridges
  // (55 mm) over a saddle at the walls' top (36 mm). One candidate per rock,
  // each click on its own rock, the rock map telling the two apart.
  const Eigen::Vector3d a(-40, 0, 0), b(40, 0, 0);
  const Scene s = make_scene({moved(test::ridge_rock(), a), moved(test::ridge_rock(), b)});
  std::vector<std::byte> block;
  DetectionBudget budget;
  budget.factor = kFactor;
  const RockMapShape shape = rock_map_shape(budget);
  std::vector<std::uint8_t> map(shape.cells());
  auto d = detect(s, block, map);
  ASSERT_TRUE(d.ok()) << d.error().message;
  ASSERT_EQ(d->count, 2);
  auto top = [&](const Eigen::Vector3d& at) {
    return *project(s.rig.left, at + Eigen::Vector3d(0, 0, 50));
  };
  int on_a = 0;
  for (int k = 0; k < 2; ++k) {
    const RockCandidate& r = d->rocks[k];
    EXPECT_NEAR(r.height_mm, 55.0, 4.0);
    EXPECT_LT(r.size_mm, 100.0 * 1.15);  // one rock's diagonal at most, not the pair's
    const Eigen::Vector2d click(r.click_u, r.click_v);
    const bool a_side = (click - top(a)).norm() < (click - top(b)).norm();
    on_a += a_side ? 1 : 0;
    auto rc = s.rectifier.to_rectified(StereoSide::left, click);
    ASSERT_TRUE(rc.ok());
    const int cell = kFactor * shape.step;
    const int mx = static_cast<int>(rc->x()) / cell, my = static_cast<int>(rc->y()) / cell;
    EXPECT_EQ(map[static_cast<std::size_t>(my * shape.w + mx)], k) << "rock " << k;
  }
  EXPECT_EQ(on_a, 1);  // one click on each rock
}

TEST(RockDetection, BareGroundIsNoRockNotAnError) {
  const Scene s = make_scene({});
  std::vector<std::byte> block;
  auto d = detect(s, block);
  ASSERT_TRUE(d.ok()) << d.error().message;
  EXPECT_EQ(d->count, 0);
}

TEST(RockDetection, ASmallStoneIsNotARock) {
  // 12 mm high, 24 x 18 mm: under the grinder's 20 mm disc across, 8 mm high.
  const test::Rock stone = moved(test::ridge_rock(12, 9, 12, 10), {0, 0, 0});
  const Scene s = make_scene({stone});
  std::vector<std::byte> block;
  auto d = detect(s, block);
  ASSERT_TRUE(d.ok()) << d.error().message;
  EXPECT_EQ(d->count, 0);
}

TEST(RockDetection, RefusesAMapOutsideTheGrid) {
  Scene s = make_scene({});
  s.grid = {10, 10, 300, 100};  // wider than the 256-wide grid
  std::vector<std::byte> block;
  auto d = detect(s, block);
  ASSERT_FALSE(d.ok());
  EXPECT_EQ(d.code(), Errc::invalid_argument);
}

}  // namespace
}  // namespace petra
