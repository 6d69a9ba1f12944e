// The README's main job end to end: `petra demo` simulates a scene, starts
// petra-fsw, sends SELECT_ROI + EVALUATE over loopback UDP and writes the
// grind planes it receives as telemetry (planes.json). They must equal a
// direct run of the onboard chain (algo::Pipeline) on the same pair with
// the flight parameters, value for value, and score against the scene's
// truth.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "algo/camera/calib_json.hpp"
#include "algo/chain/pipeline.hpp"
#include "cmd/param_defs.hpp"
#include "fsw/flight_pipeline_job.hpp"
#include "sim/io/image_io.hpp"
#include "sim/score/plane_score.hpp"
#include "sim/score/planes_file.hpp"
#include "sim/score/truth_file.hpp"
#include "tests/support/text.hpp"

namespace petra {
namespace {

namespace fs = std::filesystem;

TEST(FswGrindPlanes, TelemetryEqualsTheOnboardChainOnTheSamePair) {
  const fs::path dir = fs::temp_directory_path() / ("petra_planes_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  const std::string cmd = std::string(PETRA_CLI_BIN) + " demo --seed 3 --fsw " + PETRA_FSW_BIN +
                          " --out " + dir.string() + " --timeout-s 280 > " +
                          (dir.string() + ".txt") + " 2>&1";
  const int status = std::system(cmd.c_str());
  const std::string log = test::read_all(dir.string() + ".txt");
  ASSERT_EQ(status, 0) << log;
  // `petra eval` on the ground, on the flight's points budget, agrees.
  EXPECT_NE(log.find("identical grind planes"), std::string::npos) << log;

  // What came down as telemetry.
  auto received = sim::parse_planes_json(test::read_all(dir / "planes.json"));
  ASSERT_TRUE(received.ok()) << log;
  ASSERT_FALSE(received->planes.empty()) << log;

  // The same pair, the same request, the flight parameters, in this process.
  auto rig = parse_calib_json(test::read_all(dir / "scene/calib.json"));
  ASSERT_TRUE(rig.ok());
  auto truth = sim::parse_truth_json(test::read_all(dir / "scene/truth.json"));
  ASSERT_TRUE(truth.ok());
  auto left = io::read_gray_image((dir / "pairs/left.pgm").string());
  auto right = io::read_gray_image((dir / "pairs/right.pgm").string());
  ASSERT_TRUE(left.ok() && right.ok());
  PipelineBudget budget;
  budget.image_width = left->width;
  budget.image_height = left->height;
  budget.max_roi_width = std::min(640, left->width);
  budget.max_roi_height = std::min(480, left->height);
  {
    // The flight default's points budget: one per 2x2 pixels of the rectified
    // bound, with this rig, of the default ROI budget (docs/memory.md).
    fsw::JobBudget flight;
    flight.max_width = left->width;
    flight.max_height = left->height;
    flight.rig = &*rig;
    budget.max_points = points_of(fsw::FlightPipelineJob::sizing(flight).pipeline);
  }
  PipelineParams params;
  params.shadow_fraction = param_default(ParamId::SHADOW_FRACTION);
  budget.max_disparities = params.range.search_max_px - params.range.search_min_px + 1;
  std::vector<std::byte> block(Pipeline::arena_bytes(budget, params));
  Arena arena(block);
  auto pipeline = Pipeline::create(*rig, budget, params, arena);
  ASSERT_TRUE(pipeline.ok()) << pipeline.error().message;
  PipelineRequest req;
  req.roi = truth->roi;
  req.planes = truth->planes;
  auto out = pipeline->run(left->view(), right->view(), req, StepClock{});
  ASSERT_TRUE(out.ok()) << out.error().message;
  const ReconstructionOutput& r = out->result;

  ASSERT_EQ(static_cast<int>(received->planes.size()), r.planes.accepted) << log;
  for (int k = 0; k < r.planes.accepted; ++k) {
    const GrindPlane& want = r.planes.planes[k];
    const sim::OutputPlane& got = received->planes[static_cast<std::size_t>(k)];
    EXPECT_EQ(got.normal, want.normal) << "plane " << k;
    EXPECT_EQ(got.centroid_mm, want.centroid_mm) << "plane " << k;
    EXPECT_EQ(got.area_mm2, want.area_mm2) << "plane " << k;
    EXPECT_EQ(got.rms_mm, want.rms_mm) << "plane " << k;
    EXPECT_EQ(got.triangles, static_cast<long long>(want.triangles)) << "plane " << k;
  }
  ASSERT_TRUE(received->ground.has_value());
  EXPECT_EQ(received->ground->normal, r.ground.plane.normal);
  EXPECT_EQ(received->ground->d_mm, r.ground.plane.d);

  // And they are right: every plane lies on a true face of the rock.
  const sim::PlaneScore score = sim::score_planes(*truth, *received);
  for (const sim::FacetScore& f : score.facets) {
    if (f.plane < 0) continue;
    EXPECT_LT(f.normal_error_deg, 10.0) << "facet " << f.facet << "\n" << log;
    EXPECT_LT(f.centroid_plane_distance_mm, 3.0) << "facet " << f.facet << "\n" << log;
  }
  // The pictures came down and were written.
  EXPECT_TRUE(fs::exists(dir / "overlay_1.png")) << log;
  EXPECT_TRUE(fs::exists(dir / "disparity_1.png")) << log;
  fs::remove_all(dir);
  fs::remove(dir.string() + ".txt");
}

}  // namespace
}  // namespace petra
