#include "algo/chain/reconstruction.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "tests/support/angles.hpp"
#include "tests/support/heap_counter.hpp"
#include "tests/support/synthetic_disparity.hpp"
#include "tests/support/test_rig.hpp"

namespace petra {
namespace {

struct Scene {
  StereoRig rig;
  RectifiedPair pair;
  test::Rock rock = test::ridge_rock();
  test::SyntheticDisparity disp;
};

Scene make_setup(double noise_px, std::uint64_t seed = 1) {
  Scene s;
  s.rig = test::looking_rig(seed);
  s.pair = *rectify_geometry(s.rig, 1024, 768);
  const Rect roi = test::rock_box(s.pair, s.rock, 40, 30, 55, 30);
  s.disp = test::render_disparity(s.pair, roi, s.rock, noise_px, seed);
  return s;
}

std::uint64_t fake_clock(void* ctx) {
  return (*static_cast<std::uint64_t*>(ctx) += 1000);
}

TEST(Reconstruction, DisparityToRankedPlanesOnARidgeRock) {
  const Scene s = make_setup(0.0);
  ReconstructionBudget budget;
  std::vector<std::byte> block(reconstruction_arena_bytes(budget));
  Arena arena(block);
  ReconstructionRequest req;
  req.planes = 3;
  std::uint64_t t = 0;
  StepClock clock{fake_clock, &t};
  StepTimings timings;
  test::HeapScope scope;
  auto r = reconstruct(s.rig, s.pair, s.disp.view(), req, ReconstructionParams{}, budget, arena,
                       clock, timings);
  EXPECT_EQ(scope.allocations(), 0u);
  ASSERT_TRUE(r.ok()) << r.error().message;
  EXPECT_LE(arena.high_water(), reconstruction_arena_bytes(budget));
  EXPECT_EQ(timings.count, 7u);
  EXPECT_STREQ(timings.steps[0].name, "mean filter");
  EXPECT_STREQ(timings.steps[4].name,
               "normals");  // before segmentation: the click region uses them
  EXPECT_STREQ(timings.steps[5].name, "segmentation");
  EXPECT_STREQ(timings.steps[6].name, "grind planes");
  EXPECT_EQ(timings.steps[2].ns, 1000u);
  const auto& st = r->stats;
  EXPECT_EQ(st.dense_points, static_cast<long>(s.disp.q4.size()));  // every pixel hits
  EXPECT_GT(st.filtered_points, st.dense_points * 95 / 100);
  EXPECT_EQ(st.triangulated, static_cast<std::size_t>(st.filtered_points));
  EXPECT_GT(st.disparity_max_px, st.disparity_min_px);
  EXPECT_LT(test::angle_deg(r->ground.plane.normal, Eigen::Vector3d::UnitZ()), 0.1);
  EXPECT_NEAR(r->ground.plane.d, 0.0, 0.5);
  ASSERT_EQ(r->planes.accepted, 3);
  for (int k = 0; k < 3; ++k) {
    const GrindPlane& p = r->planes.planes[k];
    double best = 180;
    for (const auto& f : s.rock.faces) best = std::min(best, test::angle_deg(p.normal, f.n));
    EXPECT_LT(best, 0.5) << "plane " << k;
  }
  // Products: every vertex classified, plane vertices present.
  std::size_t plane_vertices = 0;
  for (auto v : r->vertex_class) plane_vertices += v >= kVertexPlane0;
  EXPECT_GT(plane_vertices, 1000u);
  EXPECT_EQ(r->mesh_class.size(), r->mesh.size());
}

TEST(Reconstruction, BudgetAndRequestAreChecked) {
  const Scene s = make_setup(0.0);
  ReconstructionBudget small;
  small.max_roi_width = 64;
  std::vector<std::byte> block(reconstruction_arena_bytes(ReconstructionBudget{}));
  Arena arena(block);
  StepTimings timings;
  auto r = reconstruct(s.rig, s.pair, s.disp.view(), {}, {}, small, arena, {}, timings);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(std::string(r.error().message).find("exceeds the budget"), std::string::npos);
  ReconstructionBudget few;
  few.max_points = 1000;
  arena.reset();
  r = reconstruct(s.rig, s.pair, s.disp.view(), {}, {}, few, arena, {}, timings);
  // More valid disparities than points: the points come from a pixel stride
  // chosen so they fit, the smallest such stride.
  ASSERT_TRUE(r.ok()) << r.error().message;
  const int stride = r->stats.point_stride;
  EXPECT_GT(stride, 1);
  EXPECT_GT(r->stats.filtered_points, 1000);
  EXPECT_LE(r->stats.triangulated, 1000u);
  long finer = 0;  // valid disparities on the next smaller stride: more than the budget
  for (int y = 0; y < r->filtered.q4.height(); y += stride - 1)
    for (int x = 0; x < r->filtered.q4.width(); x += stride - 1)
      finer += is_valid_disparity(r->filtered.q4(x, y)) ? 1 : 0;
  EXPECT_GT(finer, 1000);
  for (const PixelPos& p : r->pixels) {
    EXPECT_EQ((p.u - r->filtered.roi.x) % stride, 0);
    EXPECT_EQ((p.v - r->filtered.roi.y) % stride, 0);
  }
  ReconstructionRequest req;
  req.planes = 0;
  arena.reset();
  r = reconstruct(s.rig, s.pair, s.disp.view(), req, {}, ReconstructionBudget{}, arena, {},
                  timings);
  EXPECT_EQ(r.code(), Errc::out_of_range);
}

// The caller's cancel flag, raised when a given step starts: the run ends at
// the next step boundary with Errc::cancelled and runs nothing after it.
struct CancelAt {
  PipelineStep step;
  bool raised = false;
  static void on_step(void* self, PipelineStep step, bool running) {
    auto* c = static_cast<CancelAt*>(self);
    if (running && step == c->step) c->raised = true;
  }
  static bool requested(void* self) { return static_cast<CancelAt*>(self)->raised; }
};

TEST(Reconstruction, CancelStopsAtTheNextStepBoundary) {
  const Scene s = make_setup(0.0);
  ReconstructionBudget budget;
  std::vector<std::byte> block(reconstruction_arena_bytes(budget));
  Arena arena(block);
  ReconstructionRequest req;
  req.planes = 3;
  CancelAt cancel{PipelineStep::triangulate};
  const StepClock clock{nullptr, &cancel, &CancelAt::on_step, &CancelAt::requested};
  StepTimings timings;
  auto r = reconstruct(s.rig, s.pair, s.disp.view(), req, ReconstructionParams{}, budget, arena,
                       clock, timings);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.code(), Errc::cancelled);
  EXPECT_STREQ(r.error().message, "cancelled before delaunay");
  ASSERT_EQ(timings.count, 2u);  // mean filter and triangulate ran, nothing after
  EXPECT_STREQ(timings.steps[1].name, "triangulate");

  // Not raised: the same run completes.
  CancelAt never{PipelineStep::plane_refinement};  // the pipeline's, not reconstruct's
  const StepClock quiet{nullptr, &never, &CancelAt::on_step, &CancelAt::requested};
  timings = {};
  arena.reset();
  r = reconstruct(s.rig, s.pair, s.disp.view(), req, ReconstructionParams{}, budget, arena, quiet,
                  timings);
  ASSERT_TRUE(r.ok()) << r.error().message;
  EXPECT_EQ(timings.count, 7u);
}

}  // namespace
}  // namespace petra
