// EvaluationService: the evaluation beside the arm, behind EvaluationPort.
// Owns the operator's selection (built once from SELECT_ROI, carried as is
// to the pipeline), the PipelineRunner and its worker, the running
// evaluation's id and times, and the last evaluation's planes; publishes
// each result as EVAL_RESULT, GROUND_PLANE, GRIND_PLANE packets, products
// and events. init() takes every buffer; after it nothing is allocated.
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
  Status start(const EvalFrame& frame) override;
  EvalProgress poll() override;
  void abort() override;
  EvalStatus status() const override;
  const tlm::GrindPlane* plane(std::size_t rank) const override;

 private:
  EvalRequest request_for(const EvalFrame& frame) const;
  std::int64_t elapsed_ns() const { return w_.clock->monotonic_ns() - started_ns_; }
  bool publish();  // false: the run failed
  tlm::EvalResult result_summary() const;
  void push_planes(const EvalOutput& out, tlm::TmTime t);
  void stage_products(const EvalOutput& out);

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
};

}  // namespace petra::fsw
