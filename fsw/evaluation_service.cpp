#include "fsw/evaluation_service.hpp"

namespace petra::fsw {

namespace {}  // namespace

PipelineRequest selection_from(const cmd::SelectRoiArgs& a) {
  PipelineRequest r;
  r.roi = Rect{a.x_px, a.y_px, a.w_px, a.h_px};
  r.planes = a.planes;
  r.has_click = a.has_click != 0;
  r.click_u = a.click_u_px;
  r.click_v = a.click_v_px;
  return r;  // the method is the MATCH_METHOD in force at EVALUATE
}

ProposalRequest proposal_request_from(const cmd::ProposeArgs& a) {
  ProposalRequest r;
  r.region = Rect{a.x_px, a.y_px, a.w_px, a.h_px};
  r.max_proposals = a.count;
  r.weights = {a.weight_grindable, a.weight_reach, a.weight_certainty, a.weight_size};
  return r;
}

Status EvaluationService::init(const EvaluationWiring& wiring) {
  PETRA_ASSERT(wiring.clock != nullptr && wiring.params != nullptr && wiring.events != nullptr &&
               wiring.queue != nullptr && wiring.products != nullptr);
  w_ = wiring;
  return runner_.init(w_.job, w_.arena, w_.budget, w_.rig, w_.worker_stack_bytes, w_.health,
                      w_.clock);
}

Reason EvaluationService::refusal() const {
  if (!selection_) return Reason::NO_ROI;
  if (!runner_.has_job()) return Reason::NO_PIPELINE;
  return Reason::NONE;
}

EvalRequest EvaluationService::request_for(const EvalFrame& frame) {
  frame_ = frame.sequence;
  const ParamTable& p = *w_.params;
  EvalRequest r;
  r.eval_id = eval_id_;
  r.frame = frame.sequence;
  r.left = frame.left;
  r.right = frame.right;
  r.rig = w_.rig;
  r.selection = selection_.value_or(PipelineRequest{});  // none for PROPOSE
  r.selection.method = static_cast<MatchMethod>(p.get_int(ParamId::MATCH_METHOD));
  r.disp_min_px = p.get_int(ParamId::DISP_MIN_PX);
  r.disp_max_px = p.get_int(ParamId::DISP_MAX_PX);
  r.shadow_fraction = p.get(ParamId::SHADOW_FRACTION);
  r.min_plane_area_mm2 = p.get(ParamId::MIN_PLANE_AREA_MM2);
  return r;
}

Status EvaluationService::start(const EvalFrame& frame, const ::petra::arm::JointVector& arm_pose) {
  if (refusal() != Reason::NONE)
    return Error::make(Errc::not_ready, "evaluation: no selection or no pipeline");
  ++eval_id_;  // used up even when the worker refuses: ids stay unique
  acquire_us_ = frame.acquire_us;
  EvalRequest r = request_for(frame);
  r.arm_pose = arm_pose;
  // Stamped before the worker can start: the total then always covers its steps.
  started_ns_ = w_.clock->monotonic_ns();
  PETRA_TRY(runner_.start(r));
  kind_ = JobKind::EVALUATE;
  awaiting_ = true;
  w_.events->raise(EventId::EVAL_STARTED, static_cast<std::int32_t>(r.eval_id),
                   static_cast<std::int32_t>(r.frame), r.selection.planes,
                   static_cast<std::int32_t>(r.selection.method));
  return {};
}

EvalProgress EvaluationService::poll() {
  if (awaiting_) {  // EVAL_TIMEOUT_S bounds a proposal run too
    const std::int64_t limit = w_.params->get_int(ParamId::EVAL_TIMEOUT_S) * 1000 * hal::kNsPerMs;
    if (elapsed_ns() > limit) {
      const bool propose = kind_ == JobKind::PROPOSE;
      const auto fc = static_cast<std::int32_t>(propose ? cmd::FunctionCode::PROPOSE
                                                        : cmd::FunctionCode::EVALUATE);
      w_.events->raise(EventId::EVAL_TIMEOUT,
                       static_cast<std::int32_t>(propose ? proposal_id_ : eval_id_),
                       w_.params->get_int(ParamId::EVAL_TIMEOUT_S), fc);
      return EvalProgress::TIMED_OUT;
    }
  }
  if (!runner_.poll_done()) return awaiting_ ? EvalProgress::RUNNING : EvalProgress::IDLE;
  if (!awaiting_) return EvalProgress::IDLE;  // aborted: its late result is dropped
  awaiting_ = false;
  const bool ok = kind_ == JobKind::PROPOSE ? publish_proposals() : publish();
  return ok ? EvalProgress::COMPLETED : EvalProgress::FAILED;
}

void EvaluationService::abort() {
  if (!awaiting_) return;
  runner_.cancel();
  awaiting_ = false;
  if (kind_ == JobKind::PROPOSE)
    w_.events->raise(EventId::PROPOSE_ABORTED, static_cast<std::int32_t>(proposal_id_));
  else
    w_.events->raise(EventId::EVAL_ABORTED, static_cast<std::int32_t>(eval_id_));
}

EvalStatus EvaluationService::status() const {
  EvalStatus s;
  s.running = runner_.busy();
  s.elapsed_ms = s.running && awaiting_ ? static_cast<std::uint32_t>(elapsed_ns() / hal::kNsPerMs)
                                        : elapsed_ms_;
  s.step_us = step_us_;
  s.arena_bytes = runner_.arena_capacity();
  s.arena_high_water_bytes = runner_.arena_high_water();
  return s;
}

const tlm::GrindPlane* EvaluationService::plane(std::size_t rank) const {
  return rank < planes_.size() ? &planes_[rank] : nullptr;
}

}  // namespace petra::fsw
