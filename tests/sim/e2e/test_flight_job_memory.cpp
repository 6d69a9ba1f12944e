// The flight pipeline job (fsw/flight_pipeline_job) on a simulated scene, in
// process: init once, then repeated evaluations allocate nothing, give the
// same planes every time, stay inside the arena they asked for, and refuse
// what this build cannot do by name.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "algo/camera/calib_json.hpp"
#include "cmd/param_defs.hpp"
#include "fsw/flight_pipeline_job.hpp"
#include "sim/io/image_io.hpp"
#include "sim/score/truth_file.hpp"
#include "tests/support/cached_dir.hpp"
#include "tests/support/heap_counter.hpp"
#include "tests/support/text.hpp"

namespace petra {
namespace {

namespace fs = std::filesystem;

class FlightJob : public ::testing::Test {
 protected:
  // Rendered once per build tree, shared by this suite's test processes.
  static void SetUpTestSuite() {
    dir_ = test::cached_petra_output("scene_seed3", PETRA_CLI_BIN, "sim scene --seed 3");
    ASSERT_FALSE(dir_.empty()) << "petra sim scene --seed 3 failed";
  }

  void SetUp() override {
    auto rig = parse_calib_json(test::read_all(dir_ / "calib.json"));
    ASSERT_TRUE(rig.ok());
    rig_ = *rig;
    auto truth = sim::parse_truth_json(test::read_all(dir_ / "truth.json"));
    ASSERT_TRUE(truth.ok());
    auto left = io::read_gray_image((dir_ / "left.png").string());
    auto right = io::read_gray_image((dir_ / "right.png").string());
    ASSERT_TRUE(left.ok() && right.ok());
    left_ = std::move(*left);
    right_ = std::move(*right);
    budget_ = {left_.width, left_.height, 8192};
    budget_.rig = &rig_;  // as the executive gives it: sizes the rectified ROI
    request_.left = left_.view();
    request_.right = right_.view();
    request_.rig = &rig_;
    request_.selection.roi = truth->roi;
    request_.selection.planes = truth->planes;
    request_.shadow_fraction = param_default(ParamId::SHADOW_FRACTION);
    request_.min_plane_area_mm2 = param_default(ParamId::MIN_PLANE_AREA_MM2);
    request_.disp_min_px = static_cast<int>(param_default(ParamId::DISP_MIN_PX));
    request_.disp_max_px = static_cast<int>(param_default(ParamId::DISP_MAX_PX));
    block_.resize(job_.arena_bytes(budget_));
    arena_ = Arena(block_);
  }

  // PROPOSE of a region around the scene's rock (a quicker detection).
  fsw::EvalRequest propose_request() const {
    fsw::EvalRequest propose = request_;
    propose.kind = fsw::JobKind::PROPOSE;
    const Rect& t = request_.selection.roi;
    propose.proposal.region = Rect{std::max(t.x - 64, 0), std::max(t.y - 64, 0), 0, 0};
    propose.proposal.region.w = std::min(t.w + 128, left_.width - propose.proposal.region.x);
    propose.proposal.region.h = std::min(t.h + 128, left_.height - propose.proposal.region.y);
    propose.arm_pose = arm::stow_pose();
    return propose;
  }

  static fs::path dir_;
  StereoRig rig_;
  io::GrayImage left_, right_;
  fsw::JobBudget budget_;
  fsw::EvalRequest request_;
  hal::SystemClock clock_;
  fsw::FlightPipelineJob job_{clock_};
  std::vector<std::byte> block_;
  Arena arena_;
  std::atomic<bool> cancel_{false};
};

fs::path FlightJob::dir_;

TEST_F(FlightJob, RepeatedEvaluationsAllocateNothingAndAgree) {
  ASSERT_TRUE(job_.init(budget_, &rig_, arena_).ok());
  const std::size_t after_init = arena_.mark();
  EXPECT_GT(after_init, 0u);  // the tables live from init on
  fsw::EvalOutput first;
  ASSERT_TRUE(job_.run(request_, arena_, cancel_, first).ok());
  ASSERT_FALSE(first.planes.empty());
  EXPECT_FALSE(first.disparity_gray.empty());
  EXPECT_FALSE(first.overlay_rgb.empty());
  EXPECT_FALSE(first.cloud_xyz_mm.empty());
  EXPECT_LE(first.cloud_xyz_mm.size(), 3 * budget_.max_cloud_points);
  EXPECT_GT(first.step_us[static_cast<std::size_t>(fsw::Step::MATCH)], 0u);
  for (const tlm::GrindPlane& p : first.planes) {
    const double n = std::sqrt(p.normal[0] * p.normal[0] + p.normal[1] * p.normal[1] +
                               p.normal[2] * p.normal[2]);
    EXPECT_NEAR(n, 1.0, 1e-9);
    EXPECT_GT(p.area_mm2, request_.min_plane_area_mm2);
  }

  petra::test::HeapScope scope;
  for (int i = 0; i < 3; ++i) {
    arena_.release_to(after_init);  // what the runner does before each run
    fsw::EvalOutput again;
    ASSERT_TRUE(job_.run(request_, arena_, cancel_, again).ok());
    ASSERT_EQ(again.planes.size(), first.planes.size());
    for (std::size_t k = 0; k < first.planes.size(); ++k) {
      EXPECT_EQ(again.planes[k].normal, first.planes[k].normal);
      EXPECT_EQ(again.planes[k].centroid_mm, first.planes[k].centroid_mm);
    }
  }
  EXPECT_EQ(scope.allocations(), 0u);
  EXPECT_LE(arena_.high_water(), arena_.capacity());
}

TEST_F(FlightJob, RefusesWhatThisBuildCannotDoByName) {
  ASSERT_TRUE(job_.init(budget_, &rig_, arena_).ok());
  fsw::EvalOutput out;
  request_.selection.method = static_cast<MatchMethod>(2);
  const Status m = job_.run(request_, arena_, cancel_, out);
  ASSERT_FALSE(m.ok());
  EXPECT_EQ(m.code(), Errc::invalid_argument);
  EXPECT_NE(std::strstr(m.error().message, "MATCH_METHOD 2"), nullptr) << m.error().message;

  request_.selection.method = MatchMethod::dp;
  request_.selection.roi = Rect{left_.width - 10, 0, 50, 50};  // leaves the image
  const Status roi = job_.run(request_, arena_, cancel_, out);
  ASSERT_FALSE(roi.ok());
  EXPECT_EQ(roi.code(), Errc::out_of_range);
}

// MATCH_METHOD 1: the graph-cut matcher, reserved at init, finds the same
// faces as DP on the scene, and its second run allocates nothing.
TEST_F(FlightJob, GraphCutFindsTheSameFacesWithoutHeap) {
  ASSERT_TRUE(job_.init(budget_, &rig_, arena_).ok());
  const std::size_t after_init = arena_.mark();
  fsw::EvalOutput dp;
  ASSERT_TRUE(job_.run(request_, arena_, cancel_, dp).ok());
  request_.selection.method = MatchMethod::graph_cut;
  arena_.release_to(after_init);
  fsw::EvalOutput gc;
  const Status s = job_.run(request_, arena_, cancel_, gc);
  ASSERT_TRUE(s.ok()) << s.error().message;
  ASSERT_EQ(gc.planes.size(), dp.planes.size());
  for (std::size_t k = 0; k < dp.planes.size(); ++k) {
    double best = 180;
    for (const tlm::GrindPlane& g : gc.planes) {
      const double c = g.normal[0] * dp.planes[k].normal[0] + g.normal[1] * dp.planes[k].normal[1] +
                       g.normal[2] * dp.planes[k].normal[2];
      best = std::min(best, std::acos(std::clamp(c, -1.0, 1.0)) * 180 / M_PI);
    }
    EXPECT_LT(best, 3.0) << "DP plane " << k << " has no graph-cut plane within 3 deg";
  }
  petra::test::HeapScope scope;
  arena_.release_to(after_init);
  fsw::EvalOutput again;
  ASSERT_TRUE(job_.run(request_, arena_, cancel_, again).ok());
  EXPECT_EQ(scope.allocations(), 0u);
  EXPECT_LE(arena_.high_water(), arena_.capacity());
}

// The flight default budget runs its largest ROI (512 x 384, the default
// envelope) with both matchers in the arena it asked for, allocating nothing
// after a first (DP) run; its limits() are what the executive refuses beyond.
TEST_F(FlightJob, TheLargestRoiOfTheDefaultBudgetRunsBothMatchersWithoutHeap) {
  ASSERT_TRUE(job_.init(budget_, &rig_, arena_).ok());
  const fsw::JobLimits lim = job_.limits();
  ASSERT_EQ(lim.roi_width, 512);
  ASSERT_EQ(lim.roi_height, 384);
  EXPECT_EQ(lim.disparities, request_.disp_max_px - request_.disp_min_px + 1);
  const std::size_t after_init = arena_.mark();
  const Rect& t = request_.selection.roi;
  request_.selection.roi = Rect{std::clamp(t.x + t.w / 2 - 256, 0, left_.width - 512),
                                std::clamp(t.y + t.h / 2 - 192, 0, left_.height - 384), 512, 384};
  fsw::EvalOutput warm;
  ASSERT_TRUE(job_.run(request_, arena_, cancel_, warm).ok());
  for (int method : {0, 1}) {
    request_.selection.method = static_cast<MatchMethod>(method);
    petra::test::HeapScope scope;
    arena_.release_to(after_init);
    fsw::EvalOutput out;
    const Status s = job_.run(request_, arena_, cancel_, out);
    ASSERT_TRUE(s.ok()) << "method " << method << ": " << s.error().message;
    EXPECT_FALSE(out.planes.empty()) << "method " << method;
    EXPECT_EQ(scope.allocations(), 0u) << "method " << method;
    EXPECT_LE(arena_.high_water(), arena_.capacity());
  }
}

// PROPOSE and EVALUATE take turns in the same arena (the proposer built in
// the pipeline's place and back): after a first turn of each, neither
// allocates, the proposal list and the planes repeat, and every run starts
// where init left the arena.
TEST_F(FlightJob, ProposalsAndEvaluationsTakeTurnsWithoutHeap) {
  ASSERT_TRUE(job_.init(budget_, &rig_, arena_).ok());
  ASSERT_TRUE(job_.can_propose());
  const std::size_t after_init = arena_.mark();
  const fsw::EvalRequest propose = propose_request();
  auto turn = [&](const fsw::EvalRequest& r, fsw::EvalOutput& out) {
    arena_.release_to(after_init);  // what the runner does before each run
    const Status s = job_.run(r, arena_, cancel_, out);
    EXPECT_TRUE(s.ok()) << s.error().message;
    EXPECT_EQ(arena_.mark() >= after_init, true);
  };
  fsw::EvalOutput first, listed;
  turn(request_, first);
  turn(propose, listed);
  ASSERT_NE(listed.proposals, nullptr);
  ASSERT_GE(listed.proposals->count, 1) << listed.proposals->empty_reason;
  const ProposalList list = *listed.proposals;
  petra::test::HeapScope scope;
  fsw::EvalOutput again, relisted;
  turn(request_, again);
  turn(propose, relisted);
  EXPECT_EQ(scope.allocations(), 0u);
  ASSERT_EQ(again.planes.size(), first.planes.size());
  for (std::size_t k = 0; k < first.planes.size(); ++k)
    EXPECT_EQ(again.planes[k].normal, first.planes[k].normal);
  ASSERT_NE(relisted.proposals, nullptr);
  ASSERT_EQ(relisted.proposals->count, list.count);
  EXPECT_EQ(relisted.proposals->items[0].rock.roi, list.items[0].rock.roi);
  EXPECT_EQ(relisted.proposals->items[0].planes[0].normal, list.items[0].planes[0].normal);
  EXPECT_LE(arena_.high_water(), arena_.capacity());
}

// The remap tables depend on the rig and the budget only: built once at
// init, they serve EVALUATE, PROPOSE, EVALUATE again and a change of the
// parameters fixed at create (shadow fraction, disparity envelope).
TEST_F(FlightJob, TurnsAndParameterChangesKeepTheTablesOfInit) {
  ASSERT_TRUE(job_.init(budget_, &rig_, arena_).ok());
  ASSERT_TRUE(job_.can_propose());
  EXPECT_EQ(job_.table_builds(), 1u);
  const std::size_t after_init = arena_.mark();
  fsw::EvalRequest propose = propose_request();
  auto turn = [&](const fsw::EvalRequest& r) {
    arena_.release_to(after_init);  // what the runner does before each run
    fsw::EvalOutput out;
    const Status s = job_.run(r, arena_, cancel_, out);
    EXPECT_TRUE(s.ok()) << s.error().message;
  };
  turn(request_);
  turn(propose);
  turn(request_);
  EXPECT_EQ(job_.table_builds(), 1u) << "EVALUATE -> PROPOSE -> EVALUATE";
  fsw::EvalRequest changed = request_;
  changed.shadow_fraction = 0.5 * request_.shadow_fraction;
  changed.disp_min_px += 8;
  changed.disp_max_px -= 8;
  turn(changed);
  propose.shadow_fraction = changed.shadow_fraction;
  turn(propose);
  EXPECT_EQ(job_.table_builds(), 1u) << "a change of SHADOW_FRACTION, DISP_MIN_PX, DISP_MAX_PX";
}

// Parameters changed on the job's pipeline give what a pipeline built for
// them gives: the same planes, to the bit.
TEST_F(FlightJob, ChangedParametersGiveWhatAPipelineBuiltForThemGives) {
  ASSERT_TRUE(job_.init(budget_, &rig_, arena_).ok());
  const std::size_t after_init = arena_.mark();
  fsw::EvalOutput warm;
  ASSERT_TRUE(job_.run(request_, arena_, cancel_, warm).ok());
  fsw::EvalRequest changed = request_;
  changed.shadow_fraction = 0.5 * request_.shadow_fraction;
  changed.disp_min_px += 8;
  changed.disp_max_px -= 8;
  arena_.release_to(after_init);
  fsw::EvalOutput job_out;
  ASSERT_TRUE(job_.run(changed, arena_, cancel_, job_out).ok());

  using Job = fsw::FlightPipelineJob;
  const PipelineParams params =
      Job::pipeline_params({changed.shadow_fraction, changed.disp_min_px, changed.disp_max_px});
  const PipelineBudget pb = Job::pipeline_budget(budget_);
  std::vector<std::byte> block(Pipeline::arena_bytes(pb, params));
  Arena arena(block);
  auto pipeline = Pipeline::create(rig_, pb, params, arena);
  ASSERT_TRUE(pipeline.ok()) << pipeline.error().message;
  auto fresh = pipeline->run(left_.view(), right_.view(), changed.selection, {});
  ASSERT_TRUE(fresh.ok()) << fresh.error().message;
  const GrindResult& g = fresh->result.planes;
  ASSERT_GE(g.accepted, 1);
  ASSERT_LE(job_out.planes.size(), static_cast<std::size_t>(g.accepted));
  for (std::size_t k = 0; k < job_out.planes.size(); ++k) {
    EXPECT_EQ(job_out.planes[k].normal[0], g.planes[k].normal.x());
    EXPECT_EQ(job_out.planes[k].normal[2], g.planes[k].normal.z());
    EXPECT_EQ(job_out.planes[k].centroid_mm[1], g.planes[k].centroid_mm.y());
  }
  EXPECT_EQ(job_out.disparity_min, static_cast<float>(fresh->result.stats.disparity_min_px));
}

TEST_F(FlightJob, WithoutCalibrationItBootsAndSaysWhyItCannotRun) {
  ASSERT_TRUE(job_.init(budget_, nullptr, arena_).ok());
  fsw::EvalOutput out;
  const Status s = job_.run(request_, arena_, cancel_, out);
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.code(), Errc::not_ready);
  EXPECT_NE(std::strstr(s.error().message, "calib.json"), nullptr);
}

TEST_F(FlightJob, RefusesACalibrationLargerThanTheBudget) {
  const fsw::JobBudget small{left_.width / 2, left_.height / 2, 8192};
  const Status s = job_.init(small, &rig_, arena_);
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.code(), Errc::capacity_exceeded);
}

TEST_F(FlightJob, DisparityEnvelopeParametersBoundTheSearch) {
  ASSERT_TRUE(job_.init(budget_, &rig_, arena_).ok());
  const std::size_t after_init = arena_.mark();
  fsw::EvalOutput wide;
  ASSERT_TRUE(job_.run(request_, arena_, cancel_, wide).ok());
  ASSERT_FALSE(wide.planes.empty());
  // A narrower envelope that still holds the scene's disparities finds the same range.
  fsw::EvalRequest narrow = request_;
  narrow.disp_min_px = static_cast<int>(wide.disparity_min) - 20;
  narrow.disp_max_px = static_cast<int>(wide.disparity_max) + 20;
  arena_.release_to(after_init);
  fsw::EvalOutput same;
  ASSERT_TRUE(job_.run(narrow, arena_, cancel_, same).ok());
  EXPECT_EQ(same.disparity_min, wide.disparity_min);
  EXPECT_EQ(same.disparity_max, wide.disparity_max);
  ASSERT_EQ(same.planes.size(), wide.planes.size());
  // An envelope below the scene's disparities cannot find the rock where it is.
  fsw::EvalRequest below = request_;
  below.disp_min_px = 0;
  below.disp_max_px = static_cast<int>(wide.disparity_min) / 2;
  arena_.release_to(after_init);
  fsw::EvalOutput off;
  const Status s = job_.run(below, arena_, cancel_, off);
  if (s.ok()) {
    EXPECT_LE(off.disparity_max, static_cast<float>(below.disp_max_px + 8));
  }
  // Empty and over-budget envelopes are refused by name.
  fsw::EvalRequest empty = request_;
  empty.disp_min_px = 200;
  empty.disp_max_px = 100;
  arena_.release_to(after_init);
  const Status e = job_.run(empty, arena_, cancel_, off);
  EXPECT_EQ(e.code(), Errc::invalid_argument);
  EXPECT_NE(std::strstr(e.error().message, "DISP_MIN_PX 200"), nullptr) << e.error().message;
  fsw::EvalRequest huge = request_;
  huge.disp_min_px = 0;
  huge.disp_max_px = 1000;
  arena_.release_to(after_init);
  const Status h = job_.run(huge, arena_, cancel_, off);
  EXPECT_EQ(h.code(), Errc::capacity_exceeded);
  EXPECT_NE(std::strstr(h.error().message, "DISP_MAX_PX 1000"), nullptr) << h.error().message;
  // And the defaults work again afterwards.
  arena_.release_to(after_init);
  fsw::EvalOutput back;
  ASSERT_TRUE(job_.run(request_, arena_, cancel_, back).ok());
  EXPECT_EQ(back.planes.size(), wide.planes.size());
}

TEST_F(FlightJob, ARaisedCancelFlagEndsTheRunAsCancelled) {
  ASSERT_TRUE(job_.init(budget_, &rig_, arena_).ok());
  cancel_.store(true);
  fsw::EvalOutput out;
  const Status s = job_.run(request_, arena_, cancel_, out);
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.code(), Errc::cancelled);
  EXPECT_TRUE(out.planes.empty());
}

}  // namespace
}  // namespace petra
