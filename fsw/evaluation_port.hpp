// EvaluationPort: what the executive needs from the evaluation (implemented
// by fsw/evaluation_service: the selection, the pipeline worker, the step
// times, the last planes and their telemetry; and the rock proposals, which
// run on the same worker, one run at a time). As with fsw/arm_port.hpp, the
// executive starts, polls every cycle, aborts and reads a status; it keeps
// the command's acknowledgement and the mode, the service does the rest.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "algo/chain/pipeline_request.hpp"
#include "algo/core/image_view.hpp"
#include "algo/core/result.hpp"
#include "fsw/pipeline_job.hpp"
#include "tlm/event_defs.hpp"
#include "tlm/telemetry.hpp"

namespace petra::fsw {

enum class EvalProgress : std::uint8_t {
  IDLE,       // nothing awaited (an aborted run may still be unwinding: status().running)
  RUNNING,    // the worker is on it
  COMPLETED,  // published: EVAL_RESULT, planes, products, EVAL_COMPLETED
              // (a proposal run: PROPOSALS, the picture, PROPOSE_COMPLETED or _EMPTY)
  FAILED,  // published: EVAL_RESULT (status 2) and EVAL_FAILED (PROPOSALS status 2, PROPOSE_FAILED)
  TIMED_OUT,  // EVAL_TIMEOUT raised; still running until abort()
};

// The pair to evaluate: the executive's frame buffers, valid until the run ends.
struct EvalFrame {
  std::uint32_t sequence = 0;
  ConstGray8View left;
  ConstGray8View right;
  std::uint32_t acquire_us = 0;  // this EVALUATE's acquisition (its ACQUIRE step); 0: none
};

// Housekeeping's view of the evaluation.
struct EvalStatus {
  bool running = false;          // the worker is busy: ACQUIRE and EVALUATE are refused BUSY
  std::uint32_t elapsed_ms = 0;  // of the run going on, else of the last one
  std::array<std::uint32_t, kStepSlots> step_us{};  // of the last evaluation
  std::size_t arena_bytes = 0;
  std::size_t arena_high_water_bytes = 0;
};

class EvaluationPort {
 public:
  virtual ~EvaluationPort() = default;
  virtual void select(const PipelineRequest& selection) = 0;  // SELECT_ROI
  // Why EVALUATE cannot start (NO_ROI, NO_PIPELINE), asked before the pair
  // is acquired; Reason::NONE when it can.
  virtual Reason refusal() const = 0;
  // An error: the run did not start (refused, or the worker is busy).
  // arm_pose: the arm's now, from which the run judges its reach.
  virtual Status start(const EvalFrame& frame, const ::petra::arm::JointVector& arm_pose) = 0;
  virtual EvalProgress poll() = 0;  // every cycle
  // Cancels the run awaited (EVAL_ABORTED); its late result is dropped.
  virtual void abort() = 0;
  virtual EvalStatus status() const = 0;
  // A plane of the last evaluation by rank (ARM_GOTO); nullptr: no such plane.
  virtual const tlm::GrindPlane* plane(std::size_t rank) const = 0;

  // PROPOSE: why it cannot start (NO_PIPELINE, NO_PROPOSER); Reason::NONE when it can.
  virtual Reason propose_refusal() const = 0;
  // Starts a proposal run on the pair (PROPOSE_STARTED); an error: it did not start.
  virtual Status start_proposals(const EvalFrame& frame, const ProposalRequest& request,
                                 const ::petra::arm::JointVector& arm_pose) = 0;
  // A proposal of the last list published, by its proposal_id and rank (1 =
  // best); nullptr when that list is not the last one or has no such rank.
  virtual const RockProposal* proposal(std::uint32_t proposal_id, int rank) const = 0;
};

}  // namespace petra::fsw
