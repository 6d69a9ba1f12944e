// The command side of the executive: acknowledgement, dispatch by function
// code, and the handlers. Every handler either completes, fails with a
// reason, or leaves a Pending entry that a rate group completes later.
#include <cstring>

#include "fsw/executive.hpp"

namespace petra::fsw {

namespace {
constexpr std::int64_t kMs = 1000000;
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
  const bool needs_worker =
      c.code == cmd::FunctionCode::ACQUIRE || c.code == cmd::FunctionCode::EVALUATE;
  if (needs_worker && runner_.busy()) {  // an aborted run is still unwinding
    handler_rejects(c, Reason::BUSY, 0);
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
      selection_ = {true,         Rect{a.x_px, a.y_px, a.w_px, a.h_px},
                    a.planes,     a.has_click != 0,
                    a.click_u_px, a.click_v_px};
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
    case FC::ARM_GOTO:
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

Status Executive::acquire_pair() {
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
  acquire_us_ = static_cast<std::uint32_t>((deps_.clock->monotonic_ns() - start) / 1000);
  has_frame_ = true;
  frame_seq_ = meta->sequence;
  ++loop_.frames;
  const std::int64_t skew = meta->left_time_ns - meta->right_time_ns;
  events_.raise(EventId::FRAME_ACQUIRED, static_cast<std::int32_t>(frame_seq_), left_.width(),
                left_.height(), static_cast<std::int32_t>((skew < 0 ? -skew : skew) / 1000));
  if (params_.get_int(ParamId::SEND_LEFT_IMAGE) != 0)
    products_.stage_image(ProductKind::LEFT_IMAGE, frame_seq_, left_, 1,
                          params_.get_int(ParamId::LEFT_IMAGE_DECIMATION));
  return {};
}

void Executive::on_acquire(const cmd::Command& c) {
  modes_.request(Mode::ACQUIRE, fc_of(c));
  const Status s = acquire_pair();
  modes_.request(Mode::IDLE, 0);
  if (s)
    complete(fc_of(c), c.counter);
  else
    fail(fc_of(c), c.counter, Reason::CAMERA_ERROR);
}

void Executive::on_evaluate(const cmd::Command& c) {
  const auto& a = std::get<cmd::EvaluateArgs>(c.args);
  if (!selection_.valid) return fail(fc_of(c), c.counter, Reason::NO_ROI);
  if (!runner_.has_job()) return fail(fc_of(c), c.counter, Reason::NO_PIPELINE);
  if (a.acquire == 0 && !has_frame_) return fail(fc_of(c), c.counter, Reason::NO_FRAME);
  modes_.request(Mode::EVALUATE, fc_of(c));
  acquire_us_ = 0;
  if (a.acquire != 0 && !acquire_pair()) {
    modes_.request(Mode::IDLE, 0);
    return fail(fc_of(c), c.counter, Reason::CAMERA_ERROR);
  }
  EvalRequest r;
  r.eval_id = ++eval_id_;
  r.frame = frame_seq_;
  r.left = left_;
  r.right = right_;
  r.rig = has_rig_ ? &rig_ : nullptr;
  r.roi = selection_.roi;
  r.planes = selection_.planes;
  r.has_click = selection_.has_click;
  r.click_u_px = selection_.click_u_px;
  r.click_v_px = selection_.click_v_px;
  r.match_method = params_.get_int(ParamId::MATCH_METHOD);
  r.disp_min_px = params_.get_int(ParamId::DISP_MIN_PX);
  r.disp_max_px = params_.get_int(ParamId::DISP_MAX_PX);
  r.shadow_fraction = params_.get(ParamId::SHADOW_FRACTION);
  r.min_plane_area_mm2 = params_.get(ParamId::MIN_PLANE_AREA_MM2);
  // Stamped before the worker can start: the total then always covers its steps.
  eval_started_ns_ = deps_.clock->monotonic_ns();
  const Status s = runner_.start(r);
  if (!s) {
    modes_.request(Mode::IDLE, 0);
    return fail(fc_of(c), c.counter, Reason::PIPELINE_ERROR);
  }
  ++loop_.evaluations;
  pending_eval_ = {true, fc_of(c), c.counter};
  events_.raise(EventId::EVAL_STARTED, static_cast<std::int32_t>(r.eval_id),
                static_cast<std::int32_t>(r.frame), r.planes, r.match_method);
}

void Executive::poll_pipeline() {
  if (pending_eval_.active) {
    const std::int64_t limit = params_.get_int(ParamId::EVAL_TIMEOUT_S) * 1000 * kMs;
    if (deps_.clock->monotonic_ns() - eval_started_ns_ > limit) {
      ++loop_.faults;
      events_.raise(EventId::EVAL_TIMEOUT, static_cast<std::int32_t>(eval_id_),
                    params_.get_int(ParamId::EVAL_TIMEOUT_S));
      enter_safe();
      return;
    }
  }
  if (!runner_.poll_done()) return;
  if (!pending_eval_.active) return;  // aborted: its late result is dropped
  publish_evaluation();
}

void Executive::publish_evaluation() {
  const EvalOutput& out = runner_.output();
  const Status& s = runner_.status();
  const tlm::TmTime t = now_tm();
  eval_elapsed_ms_ =
      static_cast<std::uint32_t>((deps_.clock->monotonic_ns() - eval_started_ns_) / kMs);
  step_us_ = out.step_us;
  if (acquire_us_ != 0) step_us_[static_cast<std::size_t>(Step::ACQUIRE)] = acquire_us_;

  tlm::EvalResult r;
  r.eval_id = eval_id_;
  r.frame = frame_seq_;
  r.roi_px = {
      static_cast<std::uint16_t>(selection_.roi.x), static_cast<std::uint16_t>(selection_.roi.y),
      static_cast<std::uint16_t>(selection_.roi.w), static_cast<std::uint16_t>(selection_.roi.h)};
  r.planes_requested = static_cast<std::uint8_t>(selection_.planes);
  r.total_ms = eval_elapsed_ms_;
  r.step_us = step_us_;
  const Pending p = pending_eval_;
  pending_eval_.active = false;
  last_planes_.clear();
  if (!s) {
    r.status = 2;
    r.reason = static_cast<std::uint8_t>(Reason::PIPELINE_ERROR);
    queue_.push(r, t);
    events_.raise(EventId::EVAL_FAILED, static_cast<std::int32_t>(eval_id_),
                  static_cast<std::int32_t>(s.code()), static_cast<std::int32_t>(out.failed_step));
    modes_.request(Mode::IDLE, 0);
    fail(p.function_code, p.counter, Reason::PIPELINE_ERROR);
    return;
  }
  r.planes_found = static_cast<std::uint8_t>(out.planes.size());
  r.status = out.planes.size() < static_cast<std::size_t>(selection_.planes) ? 1 : 0;
  r.dense_points = out.dense_points;
  r.filtered_points = out.filtered_points;
  r.disparity_min = out.disparity_min;
  r.disparity_max = out.disparity_max;
  r.segmentation = out.segmentation;
  r.calib_vertical_offset_px = out.calib_vertical_offset_px;
  r.calib_spread_px = out.calib_spread_px;
  r.calib_features = out.calib_features;
  r.calib_verdict = out.calib_verdict;
  queue_.push(r, t);

  tlm::GroundPlane g;
  g.eval_id = eval_id_;
  g.normal = out.ground_normal;
  g.d_mm = out.ground_d_mm;
  g.points = out.ground_points;
  queue_.push(g, t);
  for (std::size_t i = 0; i < out.planes.size(); ++i) {
    const PlaneOut& po = out.planes[i];
    tlm::GrindPlane gp;
    gp.eval_id = eval_id_;
    gp.rank = static_cast<std::uint8_t>(i);
    gp.plane_count = static_cast<std::uint8_t>(out.planes.size());
    gp.normal = po.normal;
    gp.centroid_mm = po.centroid_mm;
    gp.area_mm2 = po.area_mm2;
    gp.flatness_rms_mm = po.flatness_rms_mm;
    gp.triangles = po.triangles;
    gp.verdict = po.verdict;
    gp.plane_source = po.plane_source;
    gp.normal_sigma_deg = static_cast<float>(po.normal_sigma_deg);
    gp.offset_sigma_mm = static_cast<float>(po.offset_sigma_mm);
    gp.footprint_rms_mm = static_cast<float>(po.footprint_rms_mm);
    gp.footprint_diameter_mm = static_cast<float>(po.footprint_diameter_mm);
    queue_.push(gp, t);
    (void)last_planes_.push_back(po);
  }
  const int step = params_.get_int(ParamId::THUMB_DECIMATION);
  if (!out.disparity_gray.empty())
    products_.stage_image(ProductKind::DISPARITY, eval_id_, out.disparity_gray, 1, step);
  if (!out.overlay_rgb.empty())
    products_.stage_image(ProductKind::OVERLAY, eval_id_, out.overlay_rgb, 3, step);
  if (!out.cloud_xyz_mm.empty())
    products_.stage_cloud(eval_id_, out.cloud_xyz_mm,
                          static_cast<std::size_t>(params_.get_int(ParamId::CLOUD_MAX_POINTS)));
  events_.raise(EventId::EVAL_COMPLETED, static_cast<std::int32_t>(eval_id_),
                static_cast<std::int32_t>(out.planes.size()), selection_.planes,
                static_cast<std::int32_t>(eval_elapsed_ms_));
  if (r.status == 1)
    events_.raise(EventId::FEWER_PLANES, static_cast<std::int32_t>(eval_id_),
                  static_cast<std::int32_t>(out.planes.size()), selection_.planes,
                  out.refused_verdict);
  modes_.request(Mode::IDLE, 0);
  complete(p.function_code, p.counter);
}

void Executive::on_arm(const cmd::Command& c) {
  if (deps_.arm == nullptr) return fail(fc_of(c), c.counter, Reason::ARM_UNAVAILABLE);
  if (estop_latched_) return fail(fc_of(c), c.counter, Reason::ARM_NOT_READY);  // e-stop held
  Status s;
  if (c.code == cmd::FunctionCode::ARM_GOTO) {
    const auto& a = std::get<cmd::ArmGotoArgs>(c.args);
    if (a.plane_rank >= last_planes_.size())
      return fail(fc_of(c), c.counter, Reason::NO_SUCH_PLANE);
    const PlaneOut& p = last_planes_[a.plane_rank];
    s = deps_.arm->start_goto(ArmTarget{p.normal, p.centroid_mm, a.standoff_mm});
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
    runner_.cancel();
    pending_eval_.active = false;
    events_.raise(EventId::EVAL_ABORTED, static_cast<std::int32_t>(eval_id_));
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
