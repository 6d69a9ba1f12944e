// The flight PipelineJob: the onboard chain (algo/chain/pipeline) behind the
// executive's interface (fsw/pipeline_job.hpp).
//   init: builds the rectification tables once in the worker's arena
//     (they stay for every run); with no calib.json it stays unready and
//     every run fails not_ready naming the missing file;
//   run: the request's selection (ROI, c, click; MATCH_METHOD 0 DP, 1 graph cut, whose
//     matcher is reserved at init) straight to the pipeline, then EvalOutput: accepted
//     planes (ranked, normals out of the rock) not smaller than MIN_PLANE_AREA_MM2, ground plane,
//     point counts, disparity range, step times (the injected clock) in the fsw slots
//     (fsw/step_slots.hpp), and products built in the arena
//     (disparity as 8-bit gray of the rectified ROI, an RGB overlay of the classes, the cloud in
//     mm).
// ROI size (original left image px, what SELECT_ROI carries): budget.roi_width
// x roi_height, or else 512 x 384 (the flight default), or, when only
// budget.arena_mb is given, the largest 4:3 ROI (640 x 480 down to 64 x 48)
// whose run fits it. The pipeline is sized for the largest rectified ROI any
// such ROI maps to anywhere in the image, so an ROI within limits() never
// fails for its size later; the executive refuses larger ones at the command.
// Parameters the pipeline holds (shadow fraction; DISP_MIN_PX..DISP_MAX_PX,
// the envelope the disparity-range search looks in) come from the request:
// when they differ from those in force they are set on the pipeline
// (Pipeline::set_params), the tables kept: they depend on the rig and the
// budget only. An envelope that is empty or wider than the budget's
// disparity count (the default envelope's) is refused naming both parameters.
// PROPOSE (JobKind::PROPOSE): the rock proposer (algo/propose/proposer), also
// built at init, runs every candidate through the same pipeline (same tables,
// same parameters in force), with the ROI limits (its ROIs pass SELECT_ROI's
// check) and the arm geometry of the budget. So switching between EVALUATE
// and PROPOSE rebuilds nothing (one run at a time, as the executive's are).
// Both judge the arm's reach alike (algo/propose/arm_reach: the budget's arm
// geometry, the joint limits, the request's arm pose, the default standoff):
// each face's footprint is a disc the arm reaches where it has one, so a
// proposal sent back as SELECT_ROI gives its planes again.
// Memory: arena_bytes(budget) = the tables + the larger of the pipeline's
// largest run + the products and the whole-pair detection; nothing else, no
// heap.
#pragma once

#include <cstddef>

#include "algo/chain/pipeline.hpp"
#include "algo/propose/proposer.hpp"
#include "fsw/pipeline_job.hpp"
#include "hal/clock.hpp"

namespace petra::fsw {

class FlightPipelineJob final : public PipelineJob {
 public:
  // Step times are read from `clock` (the executive's), on the worker thread.
  explicit FlightPipelineJob(const hal::Clock& clock) : clock_(&clock) {}
  // Not copied: its proposer points to its pipeline.
  FlightPipelineJob(const FlightPipelineJob&) = delete;
  FlightPipelineJob& operator=(const FlightPipelineJob&) = delete;
  const char* name() const override {
    return "onboard chain (algo/chain/pipeline, dp and graph-cut matchers)";
  }
  std::size_t arena_bytes(const JobBudget& budget) const override;
  Status init(const JobBudget& budget, const StereoRig* rig, Arena& arena) override;
  Status run(const EvalRequest& request, Arena& arena, const std::atomic<bool>& cancel,
             EvalOutput& out) override;

  JobLimits limits() const override;
  bool can_propose() const override { return proposer_fits_; }
  int describe_memory(char* buf, std::size_t size) const override;
  // Times the remap tables were built since construction (init builds them).
  std::uint32_t table_builds() const { return table_builds_; }

  // The pipeline's sizes for an executive budget and the ROI (original px) they admit.
  struct Sizing {
    petra::PipelineBudget pipeline;
    int roi_width = 0;
    int roi_height = 0;
  };
  static Sizing sizing(const JobBudget& budget);
  static petra::PipelineBudget pipeline_budget(const JobBudget& budget);
  // Arena bytes of a pipeline budget: the pipeline's (Pipeline::memory) + the products.
  static std::size_t need_bytes(const petra::PipelineBudget& b, std::size_t cloud_points);
  // What the pipeline is built for, from the parameter table's values.
  struct Settings {
    double shadow_fraction = 0;
    int disp_min_px = 0;
    int disp_max_px = 0;
    bool operator==(const Settings&) const = default;
  };
  static Settings default_settings();  // the parameter table's defaults
  static petra::PipelineParams pipeline_params(const Settings& settings);
  // The proposer's budget for a sizing: its chain's, and the ROI limits.
  static ProposerBudget proposer_budget(const Sizing& s);

 private:
  Status configure(const Settings& settings);
  Status propose(const EvalRequest& request, const StepClock& clock, EvalOutput& out);

  const hal::Clock* clock_;
  const StereoRig* rig_ = nullptr;
  Arena* arena_ = nullptr;
  std::size_t max_cloud_points_ = 0;
  petra::PipelineBudget budget_;
  int roi_width_ = 0;  // limits(), original px
  int roi_height_ = 0;
  Pipeline pipeline_;  // the one chain, built at init; the proposer's too
  Settings settings_;  // in force on pipeline_
  bool ready_ = false;
  std::uint32_t table_builds_ = 0;
  Proposer proposer_;
  bool proposer_fits_ = false;              // the arena holds it: built at init
  ::petra::arm::ArmGeometry arm_geometry_;  // the budget's: EVALUATE's reach
  ::petra::arm::JointLimits arm_limits_ = ::petra::arm::default_joint_limits();
};

}  // namespace petra::fsw
