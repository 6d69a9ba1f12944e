// The command side of the executive: acknowledgement, dispatch by function
// code, and the handlers. Every handler either completes, fails with a
// reason, or leaves a Pending entry that a rate group completes later.
#include <cstring>
#include <numbers>

#include "fsw/executive.hpp"
#include "fsw/proposal_packet.hpp"

namespace petra::fsw {

namespace {
std::uint8_t fc_of(const cmd::Command& c) {
  return static_cast<std::uint8_t>(c.code);
}
}  // namespace

void Executive::ack(std::uint8_t fc, std::uint32_t counter, AckStage stage, Reason reason,
                    std::uint16_t detail) {
  tlm::Ack a;
  a.function_code = fc;
  a.counter = counter;
  a.stage = static_cast<std::uint8_t>(stage);
  a.reason = static_cast<std::uint8_t>(reason);
  a.detail = detail;
  queue_.push(a, now_tm());
}

void Executive::complete(std::uint8_t fc, std::uint32_t counter) {
  ++cmd_.completed;
  ack(fc, counter, AckStage::COMPLETED, Reason::NONE, 0);
}

void Executive::fail(std::uint8_t fc, std::uint32_t counter, Reason reason) {
  ++cmd_.failed;
  cmd_.last_reason = reason;
  ack(fc, counter, AckStage::FAILED, reason, 0);
  events_.raise(EventId::CMD_FAILED, fc, static_cast<std::int32_t>(counter),
                static_cast<std::int32_t>(reason));
}

void Executive::handler_rejects(const cmd::Command& c, Reason reason, std::uint16_t detail) {
  ++cmd_.rejected;
  cmd_.last_reason = reason;
  events_.raise_rejection(reason, fc_of(c), detail, c.counter);
  ack(fc_of(c), c.counter, AckStage::REJECTED, reason, detail);
}

cmd::ValidationContext Executive::validation_context() const {
  cmd::ValidationContext ctx;
  ctx.key = &key_;
  ctx.last_counter = cmd_.last_counter;
  ctx.mode = modes_.mode();
  ctx.image_width = deps_.camera->width();
  ctx.image_height = deps_.camera->height();
  if (deps_.job != nullptr) {
    const JobLimits lim = deps_.job->limits();
    ctx.max_roi_width = lim.roi_width;
    ctx.max_roi_height = lim.roi_height;
    ctx.max_disparities = lim.disparities;
  }
  ctx.disp_min_px = static_cast<int>(params_.get_int(ParamId::DISP_MIN_PX));
  ctx.disp_max_px = static_cast<int>(params_.get_int(ParamId::DISP_MAX_PX));
  return ctx;
}

void Executive::handle_datagram(std::span<const std::uint8_t> datagram) {
  ++cmd_.received;
  const cmd::Verdict v = cmd::validate_command(datagram, validation_context());
  cmd_.last_function_code = v.function_code;
  // An authentic counter is used up, accepted or not; reserve_counters() stored it already.
  if (v.authenticated) cmd_.last_counter = v.command.counter;
  if (!v.ok()) {
    ++cmd_.rejected;
    cmd_.last_reason = v.reason;
    if (!throttle_.admit(v.reason)) {  // no key needed to cause it: no event or ack each time
      ++cmd_.unreported;
      return;
    }
    // The counter is reported once the HMAC verified (authentic, even if stale).
    const bool mac_ok = v.authenticated || v.reason == Reason::REPLAY;
    const std::uint32_t counter = mac_ok ? v.command.counter : 0;
    events_.raise_rejection(v.reason, v.function_code, v.detail, counter);
    ack(v.function_code, counter, AckStage::REJECTED, v.reason, v.detail);
    return;
  }
  dispatch(v.command);
}

void Executive::dispatch(const cmd::Command& c) {
  // Rejections a handler can still make, before anything changes.
  const bool needs_worker = c.code == cmd::FunctionCode::ACQUIRE ||
                            c.code == cmd::FunctionCode::EVALUATE ||
                            c.code == cmd::FunctionCode::PROPOSE;
  if (needs_worker && evaluation_.status().running) {  // an aborted run is still unwinding
    handler_rejects(c, Reason::BUSY, 0);
    return;
  }
  if (const cmd::SelectionRefusal r = pick_refusal(c); r.reason != Reason::NONE) {
    handler_rejects(c, r.reason, r.detail);  // what SELECT_ROI with its values would get
    return;
  }
  ++cmd_.accepted;
  ack(fc_of(c), c.counter, AckStage::ACCEPTED, Reason::NONE, 0);
  using FC = cmd::FunctionCode;
  switch (c.code) {
    case FC::NOOP:
      complete(fc_of(c), c.counter);
      return;
    case FC::RESET_COUNTERS: {
      const std::uint32_t last = cmd_.last_counter;
      cmd_ = CommandCounters{};
      cmd_.last_counter = last;  // the replay guard is not a statistic
      kernel_drops_base_ = uplink_.kernel_drops();
      reported_kernel_drops_ = 0;
      const std::uint32_t cycles = loop_.cycles;
      const std::uint32_t frames = loop_.frames;
      const std::uint32_t evaluations = loop_.evaluations;
      loop_ = LoopCounters{};
      loop_.cycles = cycles;
      loop_.frames = frames;
      loop_.evaluations = evaluations;
      queue_.reset_counters();
      reported_drops_ = 0;
      events_.raise(EventId::COUNTERS_RESET);
      complete(fc_of(c), c.counter);
      return;
    }
    case FC::SET_PARAM:
      on_set_param(c);
      return;
    case FC::GET_PARAM:
      send_param(std::get<cmd::GetParamArgs>(c.args).param_id);
      complete(fc_of(c), c.counter);
      return;
    case FC::DUMP_PARAMS:
      for (const ParamDesc& p : param_table()) send_param(p.id);
      complete(fc_of(c), c.counter);
      return;
    case FC::SELECT_ROI: {
      const auto& a = std::get<cmd::SelectRoiArgs>(c.args);
      evaluation_.select(selection_from(a));
      events_.raise(EventId::ROI_SELECTED, a.x_px, a.y_px, a.w_px, a.h_px);
      complete(fc_of(c), c.counter);
      return;
    }
    case FC::ACQUIRE:
      on_acquire(c);
      return;
    case FC::EVALUATE:
      on_evaluate(c);
      return;
    case FC::PROPOSE:
      on_propose(c);
      return;
    case FC::SELECT_PROPOSAL:
      on_select_proposal(c);
      return;
    case FC::ARM_GOTO:
    case FC::ARM_GOTO_PROPOSAL:
    case FC::ARM_GOTO_PROPOSAL_PLANE:
    case FC::ARM_STOW:
      on_arm(c);
      return;
    case FC::ABORT:
      on_abort(c);
      return;
    case FC::SET_MODE:
      on_set_mode(c);
      return;
  }
}

void Executive::send_param(std::uint16_t id) {
  tlm::ParamValue p;
  p.param_id = id;
  if (params_.get(id, p.value)) queue_.push(p, now_tm());
}

void Executive::on_set_param(const cmd::Command& c) {
  const auto& a = std::get<cmd::SetParamArgs>(c.args);
  if (!params_.set(a.param_id, a.value)) {  // the validator checked; kept for safety
    fail(fc_of(c), c.counter, Reason::INVALID_ARGUMENT);
    return;
  }
  update_periods();
  events_.raise(EventId::PARAM_CHANGED, a.param_id);
  send_param(a.param_id);
  complete(fc_of(c), c.counter);
}

Result<std::uint32_t> Executive::acquire_pair() {
  const std::int64_t start = deps_.clock->monotonic_ns();
  // docs/hal.md "Faults": a broken frame, a timeout or no pair within the skew
  // is retried; a lost device (io_error) is not: it would fail the same way.
  auto meta = deps_.camera->acquire(left_, right_);
  for (int attempt = 1; !meta; ++attempt) {
    events_.raise(EventId::CAMERA_FAULT, static_cast<std::int32_t>(meta.code()),
                  static_cast<std::int32_t>(frame_seq_ + 1));
    if (meta.code() == Errc::io_error || attempt >= kCameraAttempts) {
      has_frame_ = false;
      return meta.error();
    }
    meta = deps_.camera->acquire(left_, right_);
  }
  const auto us = static_cast<std::uint32_t>((deps_.clock->monotonic_ns() - start) / 1000);
  has_frame_ = true;
  frame_seq_ = meta->sequence;
  ++loop_.frames;
  const std::int64_t skew = meta->left_time_ns - meta->right_time_ns;
  events_.raise(EventId::FRAME_ACQUIRED, static_cast<std::int32_t>(frame_seq_), left_.width(),
                left_.height(), static_cast<std::int32_t>((skew < 0 ? -skew : skew) / 1000));
  if (params_.get_int(ParamId::SEND_LEFT_IMAGE) != 0)
    products_.stage_image(ProductKind::LEFT_IMAGE, frame_seq_, left_, 1,
                          params_.get_int(ParamId::LEFT_IMAGE_DECIMATION));
  return us;
}

void Executive::on_acquire(const cmd::Command& c) {
  modes_.request(Mode::ACQUIRE, fc_of(c));
  const bool acquired = acquire_pair().ok();
  modes_.request(Mode::IDLE, 0);
  if (acquired)
    complete(fc_of(c), c.counter);
  else
    fail(fc_of(c), c.counter, Reason::CAMERA_ERROR);
}

// EVALUATE and PROPOSE: into EVALUATE and, when asked, a new pair first.
// False: the command failed (CAMERA_ERROR) and the mode is IDLE again.
bool Executive::enter_evaluate(const cmd::Command& c, bool acquire, std::uint32_t& acquire_us) {
  modes_.request(Mode::EVALUATE, fc_of(c));
  acquire_us = 0;
  if (!acquire) return true;
  auto us = acquire_pair();
  if (!us) {
    modes_.request(Mode::IDLE, 0);
    fail(fc_of(c), c.counter, Reason::CAMERA_ERROR);
    return false;
  }
  acquire_us = *us;
  return true;
}

void Executive::on_evaluate(const cmd::Command& c) {
  const auto& a = std::get<cmd::EvaluateArgs>(c.args);
  const Reason refused = evaluation_.refusal();
  if (refused != Reason::NONE) return fail(fc_of(c), c.counter, refused);
  if (a.acquire == 0 && !has_frame_) return fail(fc_of(c), c.counter, Reason::NO_FRAME);
  std::uint32_t acquire_us = 0;
  if (!enter_evaluate(c, a.acquire != 0, acquire_us)) return;
  if (!evaluation_.start(EvalFrame{frame_seq_, left_, right_, acquire_us}, arm_pose())) {
    modes_.request(Mode::IDLE, 0);
    return fail(fc_of(c), c.counter, Reason::PIPELINE_ERROR);
  }
  ++loop_.evaluations;
  pending_eval_ = {true, fc_of(c), c.counter};
}

// The proposer runs as an evaluation does (mode EVALUATE, the same worker,
// EVAL_TIMEOUT_S, ABORT): while either runs, the other is refused WRONG_MODE.
void Executive::on_propose(const cmd::Command& c) {
  const auto& a = std::get<cmd::ProposeArgs>(c.args);
  const Reason refused = evaluation_.propose_refusal();
  if (refused != Reason::NONE) return fail(fc_of(c), c.counter, refused);
  if (a.acquire == 0 && !has_frame_) return fail(fc_of(c), c.counter, Reason::NO_FRAME);
  std::uint32_t acquire_us = 0;
  if (!enter_evaluate(c, a.acquire != 0, acquire_us)) return;
  if (!evaluation_.start_proposals(EvalFrame{frame_seq_, left_, right_, acquire_us},
                                   proposal_request_from(a), arm_pose())) {
    modes_.request(Mode::IDLE, 0);
    return fail(fc_of(c), c.counter, Reason::PIPELINE_ERROR);
  }
  pending_eval_ = {true, fc_of(c), c.counter};
}

// The measured joints when the arm reports them, else the stowed pose.
::petra::arm::JointVector Executive::arm_pose() const {
  tlm::ArmStatus st;
  if (deps_.arm == nullptr || !deps_.arm->status(st)) return ::petra::arm::stow_pose();
  ::petra::arm::JointVector q;
  for (int j = 0; j < ::petra::arm::kJointCount; ++j)
    q[j] =
        static_cast<double>(st.joint_deg[static_cast<std::size_t>(j)]) * std::numbers::pi / 180.0;
  return q;
}

// SELECT_PROPOSAL of a listed proposal whose ROI SELECT_ROI would refuse
// (outside the image, beyond the memory budget): that refusal, before
// acceptance. NONE otherwise (an unlisted proposal fails NO_SUCH_PROPOSAL).
cmd::SelectionRefusal Executive::pick_refusal(const cmd::Command& c) const {
  const auto* a = std::get_if<cmd::SelectProposalArgs>(&c.args);
  if (a == nullptr) return {};
  const RockProposal* p = evaluation_.proposal(a->proposal_id, a->rank);
  if (p == nullptr) return {};
  return cmd::selection_refusal(selection_args(*p), validation_context());
}

void Executive::on_select_proposal(const cmd::Command& c) {
  const auto& a = std::get<cmd::SelectProposalArgs>(c.args);
  const RockProposal* p = evaluation_.proposal(a.proposal_id, a.rank);
  if (p == nullptr) return fail(fc_of(c), c.counter, Reason::NO_SUCH_PROPOSAL);
  const cmd::SelectRoiArgs roi = selection_args(*p);  // checked by pick_refusal
  evaluation_.select(selection_from(roi));
  events_.raise(EventId::ROI_SELECTED, roi.x_px, roi.y_px, roi.w_px, roi.h_px);
  events_.raise(EventId::PROPOSAL_SELECTED, static_cast<std::int32_t>(a.proposal_id), a.rank,
                roi.planes);
  complete(fc_of(c), c.counter);
}

// The evaluation publishes its own result; the command's ack and the mode are ours.
void Executive::poll_pipeline() {
  const EvalProgress p = evaluation_.poll();
  if (p == EvalProgress::TIMED_OUT) {
    ++loop_.faults;
    enter_safe();  // aborts the evaluation and fails its command
    return;
  }
  if (p != EvalProgress::COMPLETED && p != EvalProgress::FAILED) return;
  const Pending done = pending_eval_;
  pending_eval_.active = false;
  modes_.request(Mode::IDLE, 0);
  if (p == EvalProgress::COMPLETED)
    complete(done.function_code, done.counter);
  else
    fail(done.function_code, done.counter, Reason::PIPELINE_ERROR);
}

// ARM_GOTO_PROPOSAL's target (the proposal's best offered plane) or
// ARM_GOTO_PROPOSAL_PLANE's (the plane named, when it is offered); no plane
// when the list, the rank or an offered plane is not there.
Executive::ProposalTarget Executive::proposal_target(const cmd::Command& c) const {
  if (c.code == cmd::FunctionCode::ARM_GOTO_PROPOSAL) {
    const auto& a = std::get<cmd::ArmGotoProposalArgs>(c.args);
    const RockProposal* p = evaluation_.proposal(a.proposal_id, a.rank);
    const int k = p != nullptr ? offered_plane(*p) : -1;
    return {k >= 0 ? &p->planes[k] : nullptr, a.standoff_mm};
  }
  const auto& a = std::get<cmd::ArmGotoProposalPlaneArgs>(c.args);
  const RockProposal* p = evaluation_.proposal(a.proposal_id, a.rank);
  const int k = a.plane - 1;
  return {p != nullptr && plane_offered(*p, k) ? &p->planes[k] : nullptr, a.standoff_mm};
}

void Executive::on_arm(const cmd::Command& c) {
  if (deps_.arm == nullptr) return fail(fc_of(c), c.counter, Reason::ARM_UNAVAILABLE);
  if (estop_latched_) return fail(fc_of(c), c.counter, Reason::ARM_NOT_READY);  // e-stop held
  Status s;
  if (c.code == cmd::FunctionCode::ARM_GOTO) {
    const auto& a = std::get<cmd::ArmGotoArgs>(c.args);
    const tlm::GrindPlane* p = evaluation_.plane(a.plane_rank);
    if (p == nullptr) return fail(fc_of(c), c.counter, Reason::NO_SUCH_PLANE);
    s = deps_.arm->start_goto(ArmTarget{p->normal, p->centroid_mm, a.standoff_mm});
  } else if (c.code == cmd::FunctionCode::ARM_GOTO_PROPOSAL ||
             c.code == cmd::FunctionCode::ARM_GOTO_PROPOSAL_PLANE) {
    const ProposalTarget t = proposal_target(c);
    if (t.plane == nullptr) return fail(fc_of(c), c.counter, Reason::NO_SUCH_PROPOSAL);
    const GrindPlane& g = *t.plane;
    s = deps_.arm->start_goto(ArmTarget{{g.normal.x(), g.normal.y(), g.normal.z()},
                                        {g.centroid_mm.x(), g.centroid_mm.y(), g.centroid_mm.z()},
                                        t.standoff_mm});
  } else {
    s = deps_.arm->start_stow();
  }
  if (!s) {
    return fail(fc_of(c), c.counter,
                s.code() == Errc::not_ready ? Reason::ARM_NOT_READY : Reason::ARM_REFUSED);
  }
  if (modes_.mode() == Mode::IDLE) modes_.request(Mode::ARM_MOVING, fc_of(c));
  pending_arm_ = {true, fc_of(c), c.counter};
}

void Executive::stop_activity(Reason why) {
  if (pending_eval_.active) {
    evaluation_.abort();  // EVAL_ABORTED
    pending_eval_.active = false;
    fail(pending_eval_.function_code, pending_eval_.counter, why);
  }
  if (pending_arm_.active) {
    if (deps_.arm != nullptr) deps_.arm->quick_stop();
    pending_arm_.active = false;
    fail(pending_arm_.function_code, pending_arm_.counter, why);
  }
}

void Executive::enter_safe() {
  stop_activity(Reason::ABORTED);
  products_.cancel_all();
  modes_.request(Mode::SAFE, 0);
}

void Executive::on_abort(const cmd::Command& c) {
  stop_activity(Reason::ABORTED);
  const Mode m = modes_.mode();
  if (m == Mode::EVALUATE || m == Mode::ARM_MOVING || m == Mode::ACQUIRE)
    modes_.request(Mode::IDLE, fc_of(c));
  complete(fc_of(c), c.counter);
}

void Executive::on_set_mode(const cmd::Command& c) {
  const auto to = static_cast<Mode>(std::get<cmd::SetModeArgs>(c.args).mode);
  if (to == Mode::SAFE) {
    stop_activity(Reason::ABORTED);
    products_.cancel_all();
  }
  // Leaving SAFE: an arm stopped by a drive fault reboots its drives (ARM_READY follows).
  if (to == Mode::IDLE && modes_.mode() == Mode::SAFE && deps_.arm != nullptr)
    (void)deps_.arm->reset();
  modes_.request(to, fc_of(c));
  complete(fc_of(c), c.counter);
}

}  // namespace petra::fsw
