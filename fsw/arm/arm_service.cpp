#include "fsw/arm/arm_service.hpp"

#include <cmath>
#include <numbers>

#include "hal/canopen/arm_drives.hpp"

namespace petra::fsw::arm {

namespace pa = petra::arm;

namespace {

// A stow counts as reached when every joint is this close to the stowed pose.
constexpr double kStowToleranceRad = 0.2 * pa::kRadPerDeg;

bool positive_finite(double v) {
  return std::isfinite(v) && v > 0.0;
}

}  // namespace

const char* arm_state_name(ArmState s) {
  switch (s) {
    case ArmState::off:
      return "off";
    case ArmState::booting:
      return "booting";
    case ArmState::enabling:
      return "enabling";
    case ArmState::holding:
      return "holding";
    case ArmState::moving:
      return "moving";
    case ArmState::approaching:
      return "approaching";
    case ArmState::retreating:
      return "retreating";
    case ArmState::settling:
      return "settling";
    case ArmState::stopped:
      return "stopped";
    case ArmState::fault:
      return "fault";
  }
  return "unknown";
}

const char* arm_event_name(ArmEventKind k) {
  switch (k) {
    case ArmEventKind::refused:
      return "refused";
    case ArmEventKind::started:
      return "started";
    case ArmEventKind::reached:
      return "reached";
    case ArmEventKind::verify_failed:
      return "verify_failed";
    case ArmEventKind::settle_timeout:
      return "settle_timeout";
    case ArmEventKind::drive_fault:
      return "drive_fault";
    case ArmEventKind::emergency:
      return "emergency";
    case ArmEventKind::bus_state:
      return "bus_state";
    case ArmEventKind::bad_frame:
      return "bad_frame";
    case ArmEventKind::stopped:
      return "stopped";
    case ArmEventKind::ready:
      return "ready";
  }
  return "unknown";
}

Status validate_config(const ArmServiceConfig& c) {
  PETRA_TRY(pa::validate_geometry(c.geometry));
  PETRA_TRY(pa::validate_limits(c.limits));
  if (!positive_finite(c.max_tool_speed_mm_s) || !positive_finite(c.max_tool_accel_mm_s2)) {
    return Error::make(Errc::non_positive, "arm: tool speed and acceleration must be > 0");
  }
  if (!positive_finite(c.min_standoff_mm) || !(c.max_standoff_mm > c.min_standoff_mm) ||
      c.max_standoff_mm > 500.0) {
    return Error::make(Errc::invalid_argument,
                       "arm: standoff range %g..%g mm must be within (0, 500]", c.min_standoff_mm,
                       c.max_standoff_mm);
  }
  if (!positive_finite(c.reach_tolerance_mm) || !positive_finite(c.axis_tolerance_deg)) {
    return Error::make(Errc::non_positive, "arm: verification tolerances must be > 0");
  }
  if (c.settle_timeout_ms <= 0)
    return Error::make(Errc::non_positive, "arm: settle timeout must be > 0 ms");
  if (c.heartbeat_timeout_ms != 0 && c.heartbeat_timeout_ms < kMinHeartbeatTimeoutMs)
    return Error::make(Errc::out_of_range, "arm: heartbeat timeout %u ms below %u ms",
                       c.heartbeat_timeout_ms, kMinHeartbeatTimeoutMs);
  return ok_status();
}

Status ArmService::configure(const ArmServiceConfig& config, hal::CanPort& port) {
  PETRA_TRY(validate_config(config));
  auto drives = canopen::arm_drive_configs(canopen::joint_ranges_from(config.limits));
  if (!drives) return drives.error();
  canopen::LinkTiming timing = config.timing;
  if (config.heartbeat_timeout_ms != 0) {
    for (canopen::DriveConfig& d : *drives) d.heartbeat_timeout_ms = config.heartbeat_timeout_ms;
    timing.drive_watches_master_ms = config.heartbeat_timeout_ms;
  }
  PETRA_TRY(master_.configure(*drives, timing, port));
  config_ = config;
  state_ = ArmState::off;
  goal_ = Goal::none;
  segments_.clear();
  failed_ = reached_ = near_surface_ = pending_start_ = false;
  enable_wanted_ = false;
  event_head_ = event_size_ = 0;
  return ok_status();
}

void ArmService::power_up(std::int64_t now_ms) {
  master_.boot(now_ms);
  master_.enable(now_ms);  // the links remember it and enable right after NMT start
  enable_wanted_ = true;
  state_ = ArmState::booting;
  failed_ = reached_ = false;
}

Status ArmService::reset(std::int64_t now_ms) {
  if (state_ != ArmState::fault && state_ != ArmState::off && state_ != ArmState::stopped) {
    return Error::make(Errc::not_ready, "arm reset refused while %s", arm_state_name(state_));
  }
  segments_.clear();
  pending_start_ = false;
  power_up(now_ms);
  return ok_status();
}

JointVector ArmService::measured_joints() const {
  JointVector q;
  for (int j = 0; j < pa::kJointCount; ++j)
    q[j] = master_.drive(static_cast<std::size_t>(j)).position_rad();
  return q;
}

MotionProgress ArmService::progress() const {
  switch (state_) {
    case ArmState::moving:
    case ArmState::approaching:
    case ArmState::retreating:
    case ArmState::settling:
      return MotionProgress::moving;
    case ArmState::enabling:
      return pending_start_ ? MotionProgress::moving : MotionProgress::idle;
    case ArmState::fault:
      return MotionProgress::failed;
    default:
      break;
  }
  if (failed_) return MotionProgress::failed;
  if (reached_) return MotionProgress::reached;
  return MotionProgress::idle;
}

void ArmService::push_event(ArmEventKind kind, std::uint8_t node, std::uint8_t code,
                            std::uint32_t detail) {
  if (event_size_ == kEventCapacity) {
    ++events_dropped_;
    return;
  }
  events_[(event_head_ + event_size_) % kEventCapacity] = ArmEvent{kind, node, code, detail};
  ++event_size_;
}

bool ArmService::pop_event(ArmEvent& out) {
  if (event_size_ == 0) return false;
  out = events_[event_head_];
  event_head_ = (event_head_ + 1) % kEventCapacity;
  --event_size_;
  return true;
}

Status ArmService::check_can_start() const {
  switch (state_) {
    case ArmState::holding:
    case ArmState::stopped:
      return ok_status();
    case ArmState::fault:
      return Error::make(
          Errc::not_ready, "arm in fault (drive %u %s): reset first", fault_node_,
          canopen::drive_fault_name(fault_node_ > 0 ? master_.drive(fault_node_ - 1u).fault()
                                                    : canopen::DriveFault::none));
    case ArmState::off:
    case ArmState::booting:
    case ArmState::enabling:
      return Error::make(Errc::not_ready, "arm drives not ready (%s)", arm_state_name(state_));
    default:
      return Error::make(Errc::not_ready, "arm busy (%s)", arm_state_name(state_));
  }
}

Status ArmService::plan_retreat_if_near_surface(JointVector& from) {
  if (!near_surface_) return ok_status();
  const pa::ToolPose tip = pa::forward_kinematics(config_.geometry, from);
  const Eigen::Vector3d n = surface_goal_.normal;
  const Eigen::Vector3d out_point = surface_goal_.centroid_mm + surface_goal_.standoff_mm * n;
  const double back_mm = (out_point - tip.tip_mm).dot(n);
  if (back_mm < 1.0) {
    near_surface_ = false;
    return ok_status();
  }
  // The line from where the tool is, back out along the normal to the standoff.
  pa::ApproachRequest r;
  r.centroid_mm = out_point - back_mm * n;
  r.normal = n;
  r.standoff_mm = back_mm;
  r.max_tool_speed_mm_s = config_.max_tool_speed_mm_s;
  r.max_tool_accel_mm_s2 = config_.max_tool_accel_mm_s2;
  const pa::ApproachPlan plan = pa::plan_approach(config_.geometry, config_.limits, r, from);
  if (!plan.ok()) {
    last_refusal_ = plan.refusal.reason;
    last_refusal_joint_ = static_cast<std::uint8_t>(plan.refusal.joint);
    push_event(ArmEventKind::refused, last_refusal_joint_, static_cast<std::uint8_t>(last_refusal_),
               1);
    const Error inner = plan.error(config_.limits);
    return Error::make(inner.code, "retreat: %s", inner.message);
  }
  Segment s;
  s.kind = SegmentKind::retreat;
  s.line = plan.approach;
  (void)segments_.push_back(s);
  from = plan.approach.standoff_q;
  return ok_status();
}

Status ArmService::begin(Goal goal, std::int64_t now_ms) {
  PETRA_TRY(check_can_start());
  segments_.clear();
  JointVector from = measured_joints();
  PETRA_TRY(plan_retreat_if_near_surface(from));
  JointVector to = pa::stow_pose();
  pa::StraightApproach line;
  if (goal == Goal::contact) {
    pa::ApproachRequest r;
    r.centroid_mm = contact_goal_.centroid_mm;
    r.normal = contact_goal_.normal;
    r.standoff_mm = contact_goal_.standoff_mm;
    r.max_tool_speed_mm_s = config_.max_tool_speed_mm_s;
    r.max_tool_accel_mm_s2 = config_.max_tool_accel_mm_s2;
    const pa::ApproachPlan plan = pa::plan_approach(config_.geometry, config_.limits, r, from);
    if (!plan.ok()) {
      segments_.clear();
      last_refusal_ = plan.refusal.reason;
      last_refusal_joint_ = static_cast<std::uint8_t>(plan.refusal.joint);
      push_event(ArmEventKind::refused, last_refusal_joint_,
                 static_cast<std::uint8_t>(last_refusal_), 0);
      return plan.error(config_.limits);
    }
    to = plan.approach.standoff_q;
    line = plan.approach;
  }
  auto move = pa::plan_joint_move(from, to, config_.limits);
  if (!move) {
    segments_.clear();
    return move.error();
  }
  Segment m;
  m.kind = SegmentKind::joint_move;
  m.move = *move;
  (void)segments_.push_back(m);
  if (goal == Goal::contact) {
    Segment a;
    a.kind = SegmentKind::approach;
    a.line = line;
    (void)segments_.push_back(a);
  }
  last_refusal_ = pa::ArmReason::ok;
  last_refusal_joint_ = 0;
  goal_ = goal;
  failed_ = reached_ = false;
  segment_ = 0;
  push_event(ArmEventKind::started, 0, goal == Goal::contact ? 0 : 1, 0);
  if (state_ == ArmState::stopped) {
    // Re-enable where the arm stands; the segments start once the drives are ready.
    master_.enable(now_ms);
    enable_wanted_ = true;
    pending_start_ = true;
    state_ = ArmState::enabling;
    return ok_status();
  }
  last_target_ = measured_joints();
  start_next_segment(now_ms);
  return ok_status();
}

Status ArmService::start_goto(const ArmGoal& goal, std::int64_t now_ms) {
  if (!goal.centroid_mm.allFinite() || !goal.normal.allFinite() ||
      std::abs(goal.normal.norm() - 1.0) > 1e-3) {
    return Error::make(Errc::invalid_argument,
                       "arm goto: centroid not finite or normal not a unit vector");
  }
  if (!(goal.standoff_mm >= config_.min_standoff_mm &&
        goal.standoff_mm <= config_.max_standoff_mm)) {
    return Error::make(Errc::out_of_range, "arm goto: standoff %.1f mm outside %.0f..%.0f mm",
                       goal.standoff_mm, config_.min_standoff_mm, config_.max_standoff_mm);
  }
  const ArmGoal previous = contact_goal_;
  contact_goal_ = goal;
  contact_goal_.normal.normalize();
  auto s = begin(Goal::contact, now_ms);
  if (!s) contact_goal_ = previous;
  return s;
}

Status ArmService::start_stow(std::int64_t now_ms) {
  return begin(Goal::stow, now_ms);
}

void ArmService::quick_stop() {
  master_.quick_stop();
  enable_wanted_ = false;
  pending_start_ = false;
  segments_.clear();
  goal_ = Goal::none;
  if (state_ != ArmState::fault && state_ != ArmState::off && state_ != ArmState::stopped) {
    state_ = ArmState::stopped;
    push_event(ArmEventKind::stopped, 0, 0, 0);
  }
}

Status ArmService::send_targets(const JointVector& q) {
  std::array<double, 5> t{};
  for (int j = 0; j < pa::kJointCount; ++j) t[j] = q[j];
  PETRA_TRY(master_.set_targets(t));
  last_target_ = q;
  return ok_status();
}

void ArmService::enter_fault() {
  state_ = ArmState::fault;
  failed_ = true;
  pending_start_ = false;
  segments_.clear();
  goal_ = Goal::none;
  for (std::size_t i = 0; i < master_.drive_count(); ++i) {
    if (master_.drive(i).state() == canopen::LinkState::fault) {
      fault_node_ = master_.drive(i).node_id();
      break;
    }
  }
}

void ArmService::drain_master_events() {
  canopen::MasterEvent e;
  while (master_.pop_event(e)) {
    switch (e.event) {
      case canopen::LinkEvent::fault:
        push_event(ArmEventKind::drive_fault, e.node, static_cast<std::uint8_t>(e.detail >> 24),
                   e.detail & 0xFFFFFF);
        break;
      case canopen::LinkEvent::emergency:
        push_event(ArmEventKind::emergency, e.node, 0, e.detail);
        break;
      case canopen::LinkEvent::bus_state:
        push_event(ArmEventKind::bus_state, 0, static_cast<std::uint8_t>(e.detail), 0);
        break;
      case canopen::LinkEvent::bad_frame:
        push_event(ArmEventKind::bad_frame, e.node, 0, e.detail);
        break;
      default:
        break;  // boot progress: visible in the drive states
    }
  }
}

void ArmService::run_segment(std::int64_t now_ms) {
  const Segment& seg = segments_[segment_];
  const double t = static_cast<double>(now_ms - segment_start_ms_) * 1e-3;
  JointVector q;
  bool done = false;
  if (seg.kind == SegmentKind::joint_move) {
    q = seg.move.position_at(t);
    done = t >= seg.move.duration_s();
  } else {
    const bool reverse = seg.kind == SegmentKind::retreat;
    const pa::IkSolution s = pa::approach_joints_at(config_.geometry, config_.limits, seg.line, t,
                                                    last_target_, reverse);
    if (!s.ok()) {
      // Planned points were all checked; a failure here means the plan is stale.
      quick_stop();
      failed_ = true;
      return;
    }
    q = s.q;
    done = t >= seg.line.duration_s();
    if (seg.kind == SegmentKind::approach) {
      near_surface_ = true;
      surface_goal_ = contact_goal_;
    }
  }
  if (!send_targets(q).ok()) return;  // a drive left "ready": the fault path takes over
  if (!done) return;
  if (seg.kind == SegmentKind::retreat) near_surface_ = false;
  ++segment_;
  // Every waypoint is reached before the next segment: the straight approach
  // must start from the standoff itself, not from where the lagging drives are.
  final_target_ = q;
  settle_start_ms_ = now_ms;
  state_ = ArmState::settling;
}

void ArmService::start_next_segment(std::int64_t now_ms) {
  segment_start_ms_ = now_ms;
  const SegmentKind next = segments_[segment_].kind;
  state_ = next == SegmentKind::joint_move ? ArmState::moving
           : next == SegmentKind::approach ? ArmState::approaching
                                           : ArmState::retreating;
}

void ArmService::settle(std::int64_t now_ms) {
  if (!master_.all_targets_reached()) {
    if (now_ms - settle_start_ms_ > config_.settle_timeout_ms) {
      failed_ = true;
      state_ = ArmState::holding;
      segments_.clear();
      push_event(ArmEventKind::settle_timeout, 0, 0,
                 static_cast<std::uint32_t>(now_ms - settle_start_ms_));
    }
    return;
  }
  if (segment_ < segments_.size()) {
    start_next_segment(now_ms);
    return;
  }
  const JointVector q = measured_joints();
  bool ok = false;
  if (goal_ == Goal::contact) {
    const pa::ToolPose p = pa::forward_kinematics(config_.geometry, q);
    last_tip_error_mm_ = (p.tip_mm - contact_goal_.centroid_mm).norm();
    const double c = std::clamp(-p.axis.dot(contact_goal_.normal), -1.0, 1.0);
    last_axis_error_deg_ = std::acos(c) / pa::kRadPerDeg;
    ok = last_tip_error_mm_ <= config_.reach_tolerance_mm &&
         last_axis_error_deg_ <= config_.axis_tolerance_deg;
  } else {
    const double worst = (q - pa::stow_pose()).cwiseAbs().maxCoeff();
    last_tip_error_mm_ = 0.0;
    last_axis_error_deg_ = worst / pa::kRadPerDeg;
    ok = worst <= kStowToleranceRad;
  }
  const auto um =
      static_cast<std::uint32_t>(std::lround(std::min(last_tip_error_mm_, 4.0e6) * 1000.0));
  if (ok) {
    reached_ = true;
    ++moves_completed_;
    push_event(ArmEventKind::reached, 0, goal_ == Goal::contact ? 0 : 1, um);
  } else {
    failed_ = true;
    push_event(ArmEventKind::verify_failed, 0, goal_ == Goal::contact ? 0 : 1, um);
  }
  segments_.clear();
  state_ = ArmState::holding;
}

void ArmService::step(std::int64_t now_ms) {
  master_.step(now_ms);
  drain_master_events();
  // Bus-off counts as a fault: nothing reaches the drives, and what they did
  // meanwhile (their master-heartbeat consumers) is unknown until a reboot.
  const bool bus_off = master_.bus_state() == hal::CanBusState::bus_off;
  if ((master_.any_fault() || bus_off) && state_ != ArmState::fault && state_ != ArmState::off) {
    enter_fault();
    return;
  }
  switch (state_) {
    case ArmState::booting:
    case ArmState::enabling:
      if (master_.all_in(canopen::LinkState::ready)) {
        if (state_ == ArmState::booting) push_event(ArmEventKind::ready, 0, 0, 0);
        last_target_ = measured_joints();
        if (pending_start_) {
          pending_start_ = false;
          start_next_segment(now_ms);
        } else {
          state_ = ArmState::holding;
        }
      } else if (!enable_wanted_ && master_.all_in(canopen::LinkState::operational)) {
        state_ = ArmState::stopped;  // stopped while booting: powered down, not enabled
      }
      return;
    case ArmState::moving:
    case ArmState::approaching:
    case ArmState::retreating:
      run_segment(now_ms);
      return;
    case ArmState::settling:
      settle(now_ms);
      return;
    default:
      return;
  }
}

ArmTelemetry ArmService::telemetry() const {
  ArmTelemetry t;
  t.state = state_;
  t.progress = progress();
  const JointVector q = measured_joints();
  for (int j = 0; j < pa::kJointCount; ++j) {
    t.joint_rad[j] = q[j];
    t.joint_target_rad[j] = last_target_[j];
    t.drive_state[j] = master_.drive(static_cast<std::size_t>(j)).state();
  }
  const pa::ToolPose p = pa::forward_kinematics(config_.geometry, q);
  t.tip_mm = p.tip_mm;
  t.axis = p.axis;
  t.last_refusal = last_refusal_;
  t.last_refusal_joint = last_refusal_joint_;
  t.last_tip_error_mm = last_tip_error_mm_;
  t.last_axis_error_deg = last_axis_error_deg_;
  t.fault_node = fault_node_;
  if (fault_node_ > 0) {
    t.fault = master_.drive(fault_node_ - 1u).fault();
    t.fault_detail = master_.drive(fault_node_ - 1u).fault_detail();
  }
  t.bus = master_.bus_state();
  t.moves_completed = moves_completed_;
  t.events_dropped = events_dropped_;
  t.can = master_.counters();
  return t;
}

}  // namespace petra::fsw::arm
