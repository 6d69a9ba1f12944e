// The onboard chain (algo/chain/pipeline) and `petra eval`'s products on a scene
// from the simulator's standard set, scored against its truth: plane count,
// normal and centroid errors, zero heap in the steady state, the named
// refusals, and the files (planes.json, PLY, PNG) an operator gets.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "algo/camera/calib_json.hpp"
#include "algo/chain/pipeline.hpp"
#include "algo/chain/products.hpp"
#include "sim/eval/eval_images.hpp"
#include "sim/eval/planes_json.hpp"
#include "sim/eval/ply_writer.hpp"
#include "sim/scene/scene_render.hpp"
#include "sim/scene/scene_set.hpp"
#include "sim/score/plane_score.hpp"
#include "sim/score/planes_file.hpp"
#include "sim/score/truth_file.hpp"
#include "tests/support/heap_counter.hpp"
#include "tests/support/rendered_scene.hpp"

namespace petra {
namespace {

// Standard-set entry 17 (weak boundary, slab, 3 faces, low sun); fewer edge
// samples than the set so the Debug build renders it in seconds.
using PipelineScene = test::RenderedScene;

const PipelineScene& pipeline_scene() {
  static const PipelineScene f = [] {
    sim::SceneOptions o = sim::standard_scene_set()[17];
    o.edge_supersampling = 2;
    return test::render_for_test(o);
  }();
  return f;
}

struct Run {
  std::vector<std::byte> block;
  Arena arena;
  Result<Pipeline> pipeline = Error::make(Errc::not_ready, "not created");
};

PipelineBudget budget_for(const StereoRig& rig, bool graph_cut = false) {
  PipelineBudget b;
  b.graph_cut = graph_cut;
  b.image_width = rig.left.width;
  b.image_height = rig.left.height;
  b.max_roi_width = 320;
  b.max_roi_height = 320;
  b.max_disparities = 128;
  return b;
}

std::unique_ptr<Run> make_run(const PipelineScene& f, const PipelineParams& params = {},
                              bool graph_cut = false) {
  auto r = std::make_unique<Run>();
  const PipelineBudget b = budget_for(f.rig, graph_cut);
  r->block.resize(Pipeline::arena_bytes(b, params));
  r->arena = Arena(r->block);
  r->pipeline = Pipeline::create(f.rig, b, params, r->arena);
  EXPECT_TRUE(r->pipeline.ok()) << r->pipeline.error().message;
  return r;
}

PipelineRequest request(const PipelineScene& f) {
  PipelineRequest q;
  q.roi = f.truth.roi;
  q.planes = f.truth.planes;
  return q;
}

sim::PlanesFile to_planes_file(const PipelineOutput& out) {
  auto p = sim::parse_planes_json(eval::format_planes_json(out.result));
  EXPECT_TRUE(p.ok()) << (p.ok() ? "" : p.error().message);
  return *p;
}

// planes.json, PLY and pictures of one run.
void products_are_well_formed(const PipelineOutput& run_out, const RectifiedPair& pair) {
  const PipelineOutput* out = &run_out;
  const ReconstructionOutput& r = out->result;
  // planes.json: the contract's fields, best first, reread by the scorer.
  const sim::PlanesFile planes = to_planes_file(*out);
  ASSERT_EQ(static_cast<int>(planes.planes.size()), r.planes.accepted);
  for (std::size_t k = 0; k < planes.planes.size(); ++k) {
    EXPECT_NEAR(planes.planes[k].normal.norm(), 1.0, 1e-9);
    // planes.json's centroid_mm is the face's centroid; grind_point_mm the grinder's point.
    EXPECT_LT((planes.planes[k].centroid_mm - r.planes.planes[k].face_centroid_mm).norm(), 1e-9);
    EXPECT_LT((planes.planes[k].grind_point() - r.planes.planes[k].centroid_mm).norm(), 1e-9);
    if (k > 0) {
      EXPECT_GE(planes.planes[k - 1].area_mm2, planes.planes[k].area_mm2);
    }
  }
  ASSERT_TRUE(planes.ground.has_value());
  const std::string json = eval::format_planes_json(r);
  for (const char* key :
       {"\"dense_points\"", "\"filtered_points\"", "\"disparity_min\"", "\"disparity_max\""})
    EXPECT_NE(json.find(key), std::string::npos) << key;
  // PLY: header counts match the binary payload exactly.
  const std::string mesh = eval::ply_bytes(r, out->left_rectified, true);
  const std::size_t end = mesh.find("end_header\n");
  ASSERT_NE(end, std::string::npos);
  const std::string header = mesh.substr(0, end);
  EXPECT_EQ(header.rfind("ply\nformat binary_little_endian 1.0\n", 0), 0u);
  EXPECT_NE(header.find("element vertex " + std::to_string(r.xyz_mm.size()) + "\n"),
            std::string::npos);
  EXPECT_NE(header.find("element face " + std::to_string(r.mesh.size()) + "\n"), std::string::npos);
  EXPECT_EQ(mesh.size() - end - 11, r.xyz_mm.size() * 16 + r.mesh.size() * 13);
  float first[3];
  std::memcpy(first, mesh.data() + end + 11, sizeof first);
  EXPECT_NEAR(first[2], r.xyz_mm[0].z(), 1e-3);
  const std::string cloud = eval::ply_bytes(r, out->left_rectified, false);
  EXPECT_EQ(cloud.find("element face"), std::string::npos);
  // Pictures: ROI-sized (scaled), legend below.
  const io::RgbImage d = eval::disparity_picture(out->disparity);
  const io::RgbImage o = eval::overlay_picture(*out, pair);
  EXPECT_EQ(d.width % out->roi_rectified.w, 0);
  EXPECT_EQ(o.width % out->roi_rectified.w, 0);
  EXPECT_GT(o.height, out->roi_rectified.h * (o.width / out->roi_rectified.w));
  // Every plane's colour appears in the overlay.
  for (int k = 0; k < r.planes.accepted; ++k) {
    const palette::Rgb8 c = products::class_colour(static_cast<std::uint8_t>(kVertexPlane0 + k));
    bool seen = false;
    for (int y = 0; y < o.height && !seen; ++y)
      for (int x = 0; x < o.width && !seen; ++x) {
        const std::uint8_t* p = o.at(x, y);
        seen = p[0] == c.r && p[1] == c.g && p[2] == c.b;
      }
    EXPECT_TRUE(seen) << "plane " << k + 1;
  }
}

TEST(EvalPipeline, FindsTheSceneFacesWithinTheTargetsWithoutHeap) {
  const PipelineScene& f = pipeline_scene();
  auto run = make_run(f);
  auto out = run->pipeline->run(f.products.left.image.view(), f.products.right.image.view(),
                                request(f), {});
  ASSERT_TRUE(out.ok()) << out.error().message;
  const sim::PlaneScore score = sim::score_planes(f.truth, to_planes_file(*out));
  EXPECT_TRUE(score.count_agrees) << score.output_planes << " planes for " << score.truth_planes;
  for (const sim::FacetScore& s : score.facets) {
    ASSERT_GE(s.plane, 0) << "facet " << s.facet << " unmatched";
    EXPECT_LE(s.normal_error_deg, 1.5) << "facet " << s.facet;
    EXPECT_LE(s.centroid_plane_distance_mm, 1.0) << "facet " << s.facet;
    EXPECT_TRUE(s.centroid_on_facet) << "facet " << s.facet;
  }
  ASSERT_TRUE(score.ground.has_value());
  EXPECT_LT(score.ground->normal_error_deg, 0.5);
  EXPECT_LE(run->arena.high_water(), run->arena.capacity());
  // The disparity range the coarse pass chose covers the truth's.
  EXPECT_LE(out->range.min_px, f.products.truth.disparity_min);
  EXPECT_GE(out->range.max_px, f.products.truth.disparity_max);

  // Steady state: the next run allocates nothing and gives the same planes.
  const int accepted = out->result.planes.accepted;
  const Eigen::Vector3d first_normal = out->result.planes.planes[0].normal;
  test::HeapScope scope;
  auto again = run->pipeline->run(f.products.left.image.view(), f.products.right.image.view(),
                                  request(f), {});
  EXPECT_EQ(scope.allocations(), 0u);
  ASSERT_TRUE(again.ok());
  EXPECT_EQ(again->result.planes.accepted, accepted);
  EXPECT_EQ(again->result.planes.planes[0].normal, first_normal);  // deterministic
  products_are_well_formed(*again, run->pipeline->rectifier().geometry());
}

TEST(EvalPipeline, GraphCutMatcherFindsTheSceneFacesWithoutHeap) {
  const PipelineScene& f = pipeline_scene();
  auto run = make_run(f, {}, true);
  // The graph cut's state is taken per run in the matching step (in bands), inside the bound.
  EXPECT_GT(Pipeline::run_bytes(budget_for(f.rig, true), PipelineParams{}),
            Pipeline::run_bytes(budget_for(f.rig), PipelineParams{}));
  PipelineRequest q = request(f);
  q.method = MatchMethod::graph_cut;
  auto out = run->pipeline->run(f.products.left.image.view(), f.products.right.image.view(), q, {});
  ASSERT_TRUE(out.ok()) << out.error().message;
  EXPECT_EQ(out->method, MatchMethod::graph_cut);
  EXPECT_GT(out->graph_cut.expansions, 0);
  EXPECT_GT(out->graph_cut.matched_pixels, out->roi_rectified.w * out->roi_rectified.h / 2);
  const sim::PlaneScore score = sim::score_planes(f.truth, to_planes_file(*out));
  EXPECT_TRUE(score.count_agrees) << score.output_planes << " planes for " << score.truth_planes;
  for (const sim::FacetScore& s : score.facets) {
    ASSERT_GE(s.plane, 0) << "facet " << s.facet << " unmatched";
    EXPECT_LE(s.normal_error_deg, 1.5) << "facet " << s.facet;
    EXPECT_LE(s.centroid_plane_distance_mm, 1.0) << "facet " << s.facet;
    EXPECT_TRUE(s.centroid_on_facet) << "facet " << s.facet;
  }
  EXPECT_LE(run->arena.high_water(), run->arena.capacity());

  // Steady state: the second run allocates nothing and repeats the first
  // (the graph cut's random disparity order is seeded).
  const Eigen::Vector3d first_normal = out->result.planes.planes[0].normal;
  test::HeapScope scope;
  auto again =
      run->pipeline->run(f.products.left.image.view(), f.products.right.image.view(), q, {});
  EXPECT_EQ(scope.allocations(), 0u);
  ASSERT_TRUE(again.ok()) << again.error().message;
  EXPECT_EQ(again->result.planes.planes[0].normal, first_normal);
  // The DP matcher stays available in a pipeline that reserved the graph cut.
  auto dp = run->pipeline->run(f.products.left.image.view(), f.products.right.image.view(),
                               request(f), {});
  ASSERT_TRUE(dp.ok()) << dp.error().message;
  EXPECT_EQ(dp->method, MatchMethod::dp);
}

std::string error_of(const Result<PipelineOutput>& r) {
  return r.ok() ? "(no error)" : r.error().message;
}

TEST(EvalPipeline, BadRequestsAreRefusedWithTheReason) {
  const PipelineScene& f = pipeline_scene();
  auto run = make_run(f);
  const ConstGray8View l = f.products.left.image.view(), r = f.products.right.image.view();
  PipelineRequest q = request(f);
  q.has_click = true;
  q.click_u = q.roi.x - 3;
  q.click_v = q.roi.y + 5;
  auto out = run->pipeline->run(l, r, q, {});
  EXPECT_NE(error_of(out).find("outside the ROI"), std::string::npos) << error_of(out);
  q = request(f);
  q.planes = 0;
  EXPECT_EQ(run->pipeline->run(l, r, q, {}).code(), Errc::out_of_range);
  q.planes = 9;
  EXPECT_NE(error_of(run->pipeline->run(l, r, q, {})).find("c = 9"), std::string::npos);
  q = request(f);
  q.roi = {1000, 700, 100, 100};
  EXPECT_NE(error_of(run->pipeline->run(l, r, q, {})).find("not inside"), std::string::npos);
  q = request(f);
  q.method = MatchMethod::graph_cut;
  EXPECT_NE(error_of(run->pipeline->run(l, r, q, {})).find("graph-cut"), std::string::npos);
  q = request(f);
  q.roi.w = 400;  // wider than the 320 px budget once rectified
  q.roi.x = 300;
  EXPECT_EQ(run->pipeline->run(l, r, q, {}).code(), Errc::capacity_exceeded);
  const ConstGray8View half(l.data(), l.width() / 2, l.height(), l.stride());
  EXPECT_EQ(run->pipeline->run(half, r, request(f), {}).code(), Errc::invalid_argument);

  // A click on shadow: a pixel deep inside a shadow region of the left view.
  PipelineParams shadowy;
  shadowy.shadow_fraction = 0.1;
  auto srun = make_run(f, shadowy);
  auto base = srun->pipeline->run(l, r, request(f), {});
  ASSERT_TRUE(base.ok()) << error_of(base);
  const ShadowMask& m = base->left_shadow;
  const Rect a = m.area;
  bool tried = false;
  for (int y = a.y + 3; y < a.y + a.h - 3 && !tried; ++y)
    for (int x = a.x + 3; x < a.x + a.w - 3 && !tried; ++x) {
      bool deep = true;
      for (int dy = -3; dy <= 3; ++dy)
        for (int dx = -3; dx <= 3; ++dx) deep = deep && m.is_shadow(x + dx, y + dy);
      if (!deep) continue;
      auto o = srun->pipeline->rectifier().to_original(StereoSide::left, {x + 0.0, y + 0.0});
      ASSERT_TRUE(o.ok());
      PipelineRequest c = request(f);
      c.has_click = true;
      c.click_u = static_cast<int>(std::lround(o->x()));
      c.click_v = static_cast<int>(std::lround(o->y()));
      if (!c.roi.contains(c.click_u, c.click_v)) continue;
      tried = true;
      auto s = srun->pipeline->run(l, r, c, {});
      EXPECT_NE(error_of(s).find("on shadow"), std::string::npos) << error_of(s);
    }
  EXPECT_TRUE(tried) << "no shadow region in the scene to click on";
}

}  // namespace
}  // namespace petra
