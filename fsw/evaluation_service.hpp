// EvaluationService: the evaluation beside the arm, behind EvaluationPort.
// Owns the operator's selection (built once from SELECT_ROI, carried as is
// to the pipeline), the PipelineRunner and its worker, the running
// evaluation's id and times, and the last evaluation's planes; publishes
// each result as EVAL_RESULT, GROUND_PLANE, GRIND_PLANE packets, products
// and events. The rock proposals (PROPOSE) run on the same worker and arena,
// so never beside an evaluation; their list is kept (for SELECT_PROPOSAL and
// ARM_GOTO_PROPOSAL) and published as PROPOSALS, the picture and events
// (fsw/proposal_publish.cpp). init() takes every buffer; after it nothing is
// allocated.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

#include "algo/core/fixed_vector.hpp"
#include "cmd/commands.hpp"
#include "fsw/evaluation_port.hpp"
#include "fsw/event_log.hpp"
#include "fsw/health.hpp"
#include "fsw/param_table.hpp"
#include "fsw/pipeline_runner.hpp"
#include "fsw/product_streamer.hpp"
#include "hal/clock.hpp"
#include "tlm/tlm_queue.hpp"

namespace petra::fsw {

// SELECT_ROI's arguments as the pipeline takes them: the one place they are read.
PipelineRequest selection_from(const cmd::SelectRoiArgs& args);
// PROPOSE's arguments as the proposer takes them (region 0 x 0: empty, the whole image).
ProposalRequest proposal_request_from(const cmd::ProposeArgs& args);

// What the service works with, all owned by the executive and given at init.
struct EvaluationWiring {
  PipelineJob* job = nullptr;  // nullptr: EVALUATE is refused NO_PIPELINE
  std::span<std::byte> arena;  // the job's arena (JobBudget sized)
  JobBudget budget;
  const StereoRig* rig = nullptr;  // nullptr: no calib file configured
  std::size_t worker_stack_bytes = 0;
  Health* health = nullptr;
  const hal::Clock* clock = nullptr;
  const ParamTable* params = nullptr;
  EventLog* events = nullptr;
  tlm::TlmQueue* queue = nullptr;
  ProductStreamer* products = nullptr;
};

class EvaluationService final : public EvaluationPort {
 public:
  Status init(const EvaluationWiring& wiring);
  void shutdown() { runner_.shutdown(); }

  void select(const PipelineRequest& selection) override { selection_ = selection; }
  Reason refusal() const override;
  Status start(const EvalFrame& frame, const ::petra::arm::JointVector& arm_pose) override;
  EvalProgress poll() override;
  void abort() override;
  EvalStatus status() const override;
  const tlm::GrindPlane* plane(std::size_t rank) const override;

  Reason propose_refusal() const override;
  Status start_proposals(const EvalFrame& frame, const ProposalRequest& request,
                         const ::petra::arm::JointVector& arm_pose) override;
  const RockProposal* proposal(std::uint32_t proposal_id, int rank) const override;

 private:
  EvalRequest request_for(const EvalFrame& frame);  // also notes the frame
  std::int64_t elapsed_ns() const { return w_.clock->monotonic_ns() - started_ns_; }
  bool publish();  // false: the run failed
  tlm::EvalResult result_summary() const;
  void push_planes(const EvalOutput& out, tlm::TmTime t);
  void stage_products(const EvalOutput& out);
  bool publish_proposals();                     // false: the run failed
  int stage_picture(const ProposalList& list);  // the step, 0: not staged

  EvaluationWiring w_;
  PipelineRunner runner_;
  std::optional<PipelineRequest> selection_;
  bool awaiting_ = false;  // a started run whose result will be published
  std::uint32_t eval_id_ = 0;
  std::uint32_t frame_ = 0;
  std::uint32_t acquire_us_ = 0;
  std::int64_t started_ns_ = 0;
  std::uint32_t elapsed_ms_ = 0;
  std::array<std::uint32_t, kStepSlots> step_us_{};
  FixedVector<tlm::GrindPlane, kMaxPlanes> planes_;
  // The run awaited or last finished, and the proposal runs' own state.
  JobKind kind_ = JobKind::EVALUATE;
  std::uint32_t proposal_id_ = 0;  // of the run awaited or last finished
  Rect proposal_region_;           // its region (the whole image when asked for it)
  ConstGray8View proposal_left_;   // the pair's left view, for the picture
  std::uint32_t listed_id_ = 0;    // the list kept below (0: none yet)
  ProposalList listed_;
};

}  // namespace petra::fsw
