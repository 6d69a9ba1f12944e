#include "hal/canopen/drive_link.hpp"

#include <cmath>

namespace petra::canopen {

namespace {

constexpr std::uint16_t kFollowingErrorCode = emcy_code::kFollowingError;

std::uint32_t counts_u32(double value) {
  const double v = std::round(std::abs(value));
  return v > 4294967295.0 ? 0xFFFFFFFFu : static_cast<std::uint32_t>(v);
}

}  // namespace

const char* link_state_name(LinkState s) {
  switch (s) {
    case LinkState::idle:
      return "idle";
    case LinkState::resetting:
      return "resetting";
    case LinkState::configuring:
      return "configuring";
    case LinkState::starting:
      return "starting";
    case LinkState::operational:
      return "operational";
    case LinkState::enabling:
      return "enabling";
    case LinkState::ready:
      return "ready";
    case LinkState::quick_stopped:
      return "quick_stopped";
    case LinkState::fault:
      return "fault";
  }
  return "unknown";
}

const char* drive_fault_name(DriveFault f) {
  switch (f) {
    case DriveFault::none:
      return "none";
    case DriveFault::boot_timeout:
      return "boot_timeout";
    case DriveFault::sdo_timeout:
      return "sdo_timeout";
    case DriveFault::sdo_abort:
      return "sdo_abort";
    case DriveFault::wrong_device:
      return "wrong_device";
    case DriveFault::start_timeout:
      return "start_timeout";
    case DriveFault::heartbeat_lost:
      return "heartbeat_lost";
    case DriveFault::nmt_state:
      return "nmt_state";
    case DriveFault::emergency:
      return "emergency";
    case DriveFault::drive_fault:
      return "drive_fault";
    case DriveFault::following_error:
      return "following_error";
    case DriveFault::enable_refused:
      return "enable_refused";
    case DriveFault::unexpected_state:
      return "unexpected_state";
  }
  return "unknown";
}

const char* link_event_name(LinkEvent e) {
  switch (e) {
    case LinkEvent::booted:
      return "booted";
    case LinkEvent::configured:
      return "configured";
    case LinkEvent::operational:
      return "operational";
    case LinkEvent::enabled:
      return "enabled";
    case LinkEvent::fault:
      return "fault";
    case LinkEvent::emergency:
      return "emergency";
    case LinkEvent::quick_stopped:
      return "quick_stopped";
    case LinkEvent::bad_frame:
      return "bad_frame";
    case LinkEvent::disabled:
      return "disabled";
    case LinkEvent::bus_state:
      return "bus_state";
  }
  return "unknown";
}

Status validate_drive_config(const DriveConfig& c) {
  if (!valid_node_id(c.node_id))
    return Error::make(Errc::out_of_range, "drive node id %u outside 1..127", c.node_id);
  const unsigned n = c.node_id;
  if (!(c.counts_per_rad > 0.0) || !std::isfinite(c.counts_per_rad)) {
    return Error::make(Errc::non_positive, "drive %u: counts_per_rad must be > 0", n);
  }
  if (c.direction != 1 && c.direction != -1)
    return Error::make(Errc::invalid_argument, "drive %u: direction must be +1 or -1", n);
  if (!std::isfinite(c.min_position_rad) || !std::isfinite(c.max_position_rad) ||
      !(c.min_position_rad < c.max_position_rad)) {
    return Error::make(Errc::invalid_argument, "drive %u: position range empty or not finite", n);
  }
  // Every reachable position must fit the drive's 32-bit position objects.
  const double span =
      std::max(std::abs(c.min_position_rad), std::abs(c.max_position_rad)) * c.counts_per_rad;
  if (span + std::abs(static_cast<double>(c.zero_counts)) > 2.0e9) {
    return Error::make(Errc::out_of_range, "drive %u: position range overflows 32-bit counts", n);
  }
  const struct {
    const char* name;
    double v;
  } positive[] = {{"profile_velocity_rad_s", c.profile_velocity_rad_s},
                  {"profile_acceleration_rad_s2", c.profile_acceleration_rad_s2},
                  {"quick_stop_deceleration_rad_s2", c.quick_stop_deceleration_rad_s2},
                  {"following_error_window_rad", c.following_error_window_rad},
                  {"position_window_rad", c.position_window_rad}};
  for (const auto& p : positive) {
    if (!(p.v > 0.0) || !std::isfinite(p.v))
      return Error::make(Errc::non_positive, "drive %u: %s must be > 0", n, p.name);
  }
  if (c.heartbeat_producer_ms == 0 || c.heartbeat_timeout_ms <= c.heartbeat_producer_ms) {
    return Error::make(Errc::invalid_argument,
                       "drive %u: heartbeat timeout %u ms must exceed the producer time %u ms", n,
                       c.heartbeat_timeout_ms, c.heartbeat_producer_ms);
  }
  return ok_status();
}

Status DriveLink::configure(const DriveConfig& config, const LinkTiming& timing) {
  PETRA_TRY(validate_drive_config(config));
  if (!valid_node_id(timing.master_node_id) || timing.master_node_id == config.node_id) {
    return Error::make(Errc::invalid_argument, "master node id %u invalid or equal to drive %u",
                       timing.master_node_id, config.node_id);
  }
  config_ = config;
  timing_ = timing;
  state_ = LinkState::idle;
  fault_ = DriveFault::none;
  build_sdo_plan();
  return ok_status();
}

std::int32_t position_to_counts(const DriveConfig& c, double rad) {
  return c.zero_counts +
         c.direction * static_cast<std::int32_t>(std::lround(rad * c.counts_per_rad));
}

double counts_to_position(const DriveConfig& c, std::int32_t counts) {
  return c.direction * static_cast<double>(counts - c.zero_counts) / c.counts_per_rad;
}

std::int32_t DriveLink::to_counts(double rad) const {
  return position_to_counts(config_, rad);
}
double DriveLink::to_rad(std::int32_t counts) const {
  return counts_to_position(config_, counts);
}

double DriveLink::position_rad() const {
  return to_rad(position_counts_);
}
double DriveLink::target_rad() const {
  return to_rad(wanted_counts_);
}

void DriveLink::build_sdo_plan() {
  const DriveConfig& c = config_;
  const std::uint8_t n = c.node_id;
  std::size_t k = 0;
  auto up = [&](SdoAddress a) { plan_[k++] = SdoStep{true, a, 0, 4}; };
  auto down = [&](SdoAddress a, std::uint32_t v, std::uint8_t size) {
    plan_[k++] = SdoStep{false, a, v, size};
  };
  up(od::kDeviceType);
  up(od::kSupportedModes);
  down(od::kProducerHeartbeat, c.heartbeat_producer_ms, 2);
  down(od::kConsumerHeartbeat,
       (static_cast<std::uint32_t>(timing_.master_node_id) << 16) | timing_.drive_watches_master_ms,
       4);
  // PDO mapping (CiA 301 7.5.2.36): disable, clear, map, count, type, enable.
  down(od::kRpdo1CobId, od::kPdoDisabled | cob_id(Function::rpdo1, n), 4);
  down(od::kRpdo1MapCount, 0, 1);
  down(od::kRpdo1Map1, od::kMapControlword, 4);
  down(od::kRpdo1Map2, od::kMapTargetPosition, 4);
  down(od::kRpdo1MapCount, 2, 1);
  down(od::kRpdo1Type, 0xFF, 1);  // act on reception
  down(od::kRpdo1CobId, cob_id(Function::rpdo1, n), 4);
  down(od::kTpdo1CobId, od::kPdoDisabled | cob_id(Function::tpdo1, n), 4);
  down(od::kTpdo1MapCount, 0, 1);
  down(od::kTpdo1Map1, od::kMapStatusword, 4);
  down(od::kTpdo1Map2, od::kMapPositionActual, 4);
  down(od::kTpdo1MapCount, 2, 1);
  down(od::kTpdo1Type, 1, 1);  // on every SYNC
  down(od::kTpdo1CobId, cob_id(Function::tpdo1, n), 4);
  down(od::kModesOfOperation, static_cast<std::uint8_t>(kModeProfilePosition), 1);
  down(od::kQuickStopOption, 6, 2);  // quick stop ramp, then hold in Quick Stop Active
  down(od::kProfileVelocity, counts_u32(c.profile_velocity_rad_s * c.counts_per_rad), 4);
  down(od::kProfileAcceleration, counts_u32(c.profile_acceleration_rad_s2 * c.counts_per_rad), 4);
  down(od::kProfileDeceleration, counts_u32(c.profile_acceleration_rad_s2 * c.counts_per_rad), 4);
  down(od::kQuickStopDeceleration, counts_u32(c.quick_stop_deceleration_rad_s2 * c.counts_per_rad),
       4);
  down(od::kFollowingErrorWindow, counts_u32(c.following_error_window_rad * c.counts_per_rad), 4);
  down(od::kPositionWindow, counts_u32(c.position_window_rad * c.counts_per_rad), 4);
  const std::int32_t a = to_counts(c.min_position_rad);
  const std::int32_t b = to_counts(c.max_position_rad);
  down(od::kSoftwareLimitMin, static_cast<std::uint32_t>(a < b ? a : b), 4);
  down(od::kSoftwareLimitMax, static_cast<std::uint32_t>(a < b ? b : a), 4);
  up(od::kPositionActual);
  plan_size_ = k;
}

void DriveLink::reboot(std::int64_t now_ms, LinkOutput& out) {
  state_ = LinkState::resetting;
  state_since_ms_ = now_ms;
  fault_ = DriveFault::none;
  fault_detail_ = 0;
  heartbeat_seen_ = false;
  plan_next_ = 0;
  sdo_pending_ = false;
  have_feedback_ = false;
  statusword_ = 0;
  setpoint_ = SetPoint::idle;
  wanted_valid_ = false;
  enable_requested_ = false;
  last_emcy_ = 0;
  out.send(make_nmt(NmtCommand::reset_communication, config_.node_id));
}

void DriveLink::enable(std::int64_t now_ms) {
  enable_requested_ = true;
  if (state_ == LinkState::operational || state_ == LinkState::quick_stopped) {
    state_ = LinkState::enabling;
    state_since_ms_ = now_ms;
  }
}

void DriveLink::quick_stop(LinkOutput& out) {
  enable_requested_ = false;
  if (state_ == LinkState::enabling || state_ == LinkState::ready) {
    state_ = LinkState::quick_stopped;
    quick_stop_reported_ = false;
    send_rpdo(controlword::kQuickStop, out);
  }
}

void DriveLink::disable(LinkOutput& out) {
  enable_requested_ = false;
  if (state_ == LinkState::enabling || state_ == LinkState::ready ||
      state_ == LinkState::quick_stopped) {
    state_ = LinkState::operational;
    send_rpdo(controlword::kDisableVoltage, out);
    out.event(config_.node_id, LinkEvent::disabled, 0);
  }
}

Status DriveLink::set_target(double rad) {
  if (state_ != LinkState::ready) {
    return Error::make(Errc::not_ready, "drive %u: target refused in state %s", config_.node_id,
                       link_state_name(state_));
  }
  if (!std::isfinite(rad) || rad < config_.min_position_rad || rad > config_.max_position_rad) {
    return Error::make(Errc::out_of_range, "drive %u: target %.4f rad outside %.4f..%.4f",
                       config_.node_id, rad, config_.min_position_rad, config_.max_position_rad);
  }
  wanted_counts_ = to_counts(rad);
  wanted_valid_ = true;
  return ok_status();
}

bool DriveLink::target_reached() const {
  if (state_ != LinkState::ready || setpoint_ != SetPoint::idle || sent_counts_ != wanted_counts_)
    return false;
  if ((statusword_ & statusword::kTargetReached) == 0) return false;
  const double window = config_.position_window_rad * config_.counts_per_rad;
  return std::abs(static_cast<double>(position_counts_) - static_cast<double>(sent_counts_)) <=
         window;
}

void DriveLink::enter_fault(DriveFault fault, std::uint32_t detail, LinkOutput& out) {
  if (state_ == LinkState::fault) return;  // keep the first cause
  const bool was_live = state_ == LinkState::enabling || state_ == LinkState::ready ||
                        state_ == LinkState::quick_stopped || state_ == LinkState::operational;
  state_ = LinkState::fault;
  fault_ = fault;
  fault_detail_ = detail;
  enable_requested_ = false;
  out.event(config_.node_id, LinkEvent::fault,
            (static_cast<std::uint32_t>(fault) << 24) | (detail & 0xFFFFFF));
  // A drive that still listens is told to stop now.
  if (was_live) send_rpdo(controlword::kQuickStop, out);
}

void DriveLink::send_rpdo(std::uint16_t controlword, LinkOutput& out) {
  out.send(make_rpdo1(config_.node_id, Rpdo1{controlword, sent_counts_}));
}

void DriveLink::send_sdo_step(std::int64_t now_ms, LinkOutput& out) {
  const SdoStep& s = plan_[plan_next_];
  SdoMessage m;
  m.kind = s.upload ? SdoKind::upload_request : SdoKind::download_request;
  m.address = s.address;
  m.value = s.value;
  m.size = s.size;
  out.send(make_sdo_request(config_.node_id, m));
  sdo_pending_ = true;
  sdo_sent_ms_ = now_ms;
}

Status DriveLink::check_upload(const SdoStep& step, std::uint32_t value) {
  if (step.address == od::kDeviceType && (value & 0xFFFF) != (od::kDeviceTypeServo & 0xFFFF)) {
    return Error::make(Errc::invalid_argument, "device type 0x%08X is not CiA 402", value);
  }
  if (step.address == od::kSupportedModes && (value & od::kSupportsProfilePosition) == 0) {
    return Error::make(Errc::invalid_argument, "supported modes 0x%08X lack profile position",
                       value);
  }
  if (step.address == od::kPositionActual) {
    position_counts_ = static_cast<std::int32_t>(value);
    sent_counts_ = wanted_counts_ = position_counts_;
  }
  return ok_status();
}

void DriveLink::on_heartbeat(const CanFrame& frame, std::int64_t now_ms, LinkOutput& out) {
  auto parsed = parse_heartbeat(frame);
  if (!parsed) {
    out.event(config_.node_id, LinkEvent::bad_frame, frame.id);
    return;
  }
  const NmtState hb = *parsed;
  last_heartbeat_ms_ = now_ms;
  heartbeat_seen_ = true;
  const auto detail = static_cast<std::uint32_t>(hb);
  switch (state_) {
    case LinkState::idle:
    case LinkState::fault:
      return;
    case LinkState::resetting:
      if (hb == NmtState::boot_up) {
        out.event(config_.node_id, LinkEvent::booted, 0);
        state_ = LinkState::configuring;
        state_since_ms_ = now_ms;
        plan_next_ = 0;
        sdo_pending_ = false;
      }
      return;  // beats from before the reset are stale
    case LinkState::configuring:
      if (hb != NmtState::preoperational) enter_fault(DriveFault::nmt_state, detail, out);
      return;
    case LinkState::starting:
      if (hb == NmtState::operational) {
        state_ = enable_requested_ ? LinkState::enabling : LinkState::operational;
        state_since_ms_ = now_ms;
        out.event(config_.node_id, LinkEvent::operational, 0);
      } else if (hb != NmtState::preoperational) {
        enter_fault(DriveFault::nmt_state, detail, out);
      }
      return;
    case LinkState::operational:
    case LinkState::enabling:
    case LinkState::ready:
    case LinkState::quick_stopped:
      if (hb != NmtState::operational) enter_fault(DriveFault::nmt_state, detail, out);
      return;
  }
}

void DriveLink::on_sdo(const CanFrame& frame, std::int64_t now_ms, LinkOutput& out) {
  auto parsed = parse_sdo(frame, true);
  if (!parsed || !sdo_pending_ || state_ != LinkState::configuring) {
    out.event(config_.node_id, LinkEvent::bad_frame, frame.id);
    return;
  }
  const SdoMessage& m = *parsed;
  const SdoStep& step = plan_[plan_next_];
  if (!(m.address == step.address)) {
    out.event(config_.node_id, LinkEvent::bad_frame, frame.id);
    return;
  }
  if (m.kind == SdoKind::abort) {
    enter_fault(DriveFault::sdo_abort, m.value, out);
    return;
  }
  const SdoKind wanted = step.upload ? SdoKind::upload_response : SdoKind::download_response;
  if (m.kind != wanted) {
    out.event(config_.node_id, LinkEvent::bad_frame, frame.id);
    return;
  }
  if (step.upload && !check_upload(step, m.value).ok()) {
    enter_fault(DriveFault::wrong_device, m.value, out);
    return;
  }
  sdo_pending_ = false;
  ++plan_next_;
  if (plan_next_ == plan_size_) {
    out.event(config_.node_id, LinkEvent::configured, 0);
    out.send(make_nmt(NmtCommand::start, config_.node_id));
    state_ = LinkState::starting;
    state_since_ms_ = now_ms;
  } else {
    send_sdo_step(now_ms, out);  // keep the configuration moving: one request in flight
  }
}

void DriveLink::on_tpdo(const CanFrame& frame, std::int64_t now_ms, LinkOutput& out) {
  (void)now_ms;
  auto parsed = parse_tpdo1(frame);
  const bool expected = state_ == LinkState::operational || state_ == LinkState::enabling ||
                        state_ == LinkState::ready || state_ == LinkState::quick_stopped ||
                        state_ == LinkState::starting;
  if (!parsed || !expected) {
    if (state_ != LinkState::fault) out.event(config_.node_id, LinkEvent::bad_frame, frame.id);
    return;
  }
  statusword_ = parsed->statusword;
  position_counts_ = parsed->position_actual;
  have_feedback_ = true;
  const DriveState ds = decode_statusword(statusword_);
  const bool drive_faulted = ds == DriveState::fault || ds == DriveState::fault_reaction_active;
  if (state_ == LinkState::ready || state_ == LinkState::quick_stopped) {
    if (drive_faulted) {
      enter_fault(DriveFault::drive_fault, statusword_, out);
    } else if (state_ == LinkState::ready && (statusword_ & statusword::kFollowingError)) {
      enter_fault(DriveFault::following_error, statusword_, out);
    } else if (state_ == LinkState::ready && ds != DriveState::operation_enabled) {
      enter_fault(DriveFault::unexpected_state, statusword_, out);
    }
  }
}

void DriveLink::on_emcy(const CanFrame& frame, LinkOutput& out) {
  auto parsed = parse_emcy(frame);
  if (!parsed) {
    out.event(config_.node_id, LinkEvent::bad_frame, frame.id);
    return;
  }
  last_emcy_ = parsed->error_code;
  out.event(config_.node_id, LinkEvent::emergency, parsed->error_code);
  if (parsed->error_code == emcy_code::kNoError) return;  // "error reset": information only
  if (state_ == LinkState::idle || state_ == LinkState::resetting) return;
  enter_fault(parsed->error_code == kFollowingErrorCode ? DriveFault::following_error
                                                        : DriveFault::emergency,
              parsed->error_code, out);
}

void DriveLink::step(std::int64_t now_ms, LinkOutput& out) {
  const std::int64_t in_state = now_ms - state_since_ms_;
  check_heartbeat(now_ms, out);
  switch (state_) {
    case LinkState::idle:
    case LinkState::fault:
      return;
    case LinkState::resetting:
      if (in_state > timing_.boot_timeout_ms) enter_fault(DriveFault::boot_timeout, 0, out);
      return;
    case LinkState::configuring:
      step_configuring(now_ms, out);
      return;
    case LinkState::starting:
      if (in_state > timing_.start_timeout_ms) enter_fault(DriveFault::start_timeout, 0, out);
      return;
    case LinkState::operational:
      if (enable_requested_) {
        state_ = LinkState::enabling;
        state_since_ms_ = now_ms;
      }
      send_rpdo(controlword::kDisableVoltage, out);  // power stage off
      return;
    case LinkState::enabling:
      step_enabling(in_state, out);
      return;
    case LinkState::ready:
      step_ready(out);
      return;
    case LinkState::quick_stopped:
      step_quick_stopped(out);
      return;
  }
}

// A drive that was heard and then goes silent in a watched state is lost.
void DriveLink::check_heartbeat(std::int64_t now_ms, LinkOutput& out) {
  const bool watching = state_ == LinkState::configuring || state_ == LinkState::starting ||
                        state_ == LinkState::operational || state_ == LinkState::enabling ||
                        state_ == LinkState::ready || state_ == LinkState::quick_stopped;
  if (watching && heartbeat_seen_ && now_ms - last_heartbeat_ms_ > config_.heartbeat_timeout_ms) {
    enter_fault(DriveFault::heartbeat_lost, static_cast<std::uint32_t>(now_ms - last_heartbeat_ms_),
                out);
  }
}

// The configuration plan: the next SDO once the last one is answered.
void DriveLink::step_configuring(std::int64_t now_ms, LinkOutput& out) {
  if (sdo_pending_ && now_ms - sdo_sent_ms_ > timing_.sdo_timeout_ms) {
    const SdoAddress a = plan_[plan_next_].address;
    enter_fault(DriveFault::sdo_timeout, (static_cast<std::uint32_t>(a.index) << 8) | a.subindex,
                out);
  } else if (!sdo_pending_) {
    send_sdo_step(now_ms, out);
  }
}

// The CiA 402 state machine walked up to operation enabled.
void DriveLink::step_enabling(std::int64_t in_state, LinkOutput& out) {
  if (in_state > timing_.enable_timeout_ms) {
    enter_fault(DriveFault::enable_refused, statusword_, out);
    return;
  }
  if (!have_feedback_) {
    send_rpdo(controlword::kDisableVoltage, out);
    return;
  }
  std::uint16_t cw = controlword::kDisableVoltage;
  switch (decode_statusword(statusword_)) {
    case DriveState::fault:
      // Fault reset acts on a rising edge of bit 7: alternate.
      fault_reset_edge_ = !fault_reset_edge_;
      cw = fault_reset_edge_ ? controlword::kFaultReset : controlword::kDisableVoltage;
      break;
    case DriveState::switch_on_disabled:
      cw = controlword::kShutdown;
      break;
    case DriveState::ready_to_switch_on:
      cw = controlword::kSwitchOn;
      break;
    case DriveState::switched_on:
    case DriveState::quick_stop_active:
      // Hold where the arm is: the target becomes the actual position.
      sent_counts_ = wanted_counts_ = position_counts_;
      cw = controlword::kEnableOperation;
      break;
    case DriveState::operation_enabled:
      sent_counts_ = wanted_counts_ = position_counts_;
      setpoint_ = SetPoint::idle;
      state_ = LinkState::ready;
      out.event(config_.node_id, LinkEvent::enabled, 0);
      cw = controlword::kEnableOperation;
      break;
    default:
      break;
  }
  send_rpdo(cw, out);
}

// Enabled: a new target goes out with the set-point handshake.
void DriveLink::step_ready(LinkOutput& out) {
  std::uint16_t cw = controlword::kEnableOperation;
  const bool acknowledged = (statusword_ & statusword::kSetPointAcknowledge) != 0;
  switch (setpoint_) {
    case SetPoint::idle:
      if (wanted_valid_ && wanted_counts_ != sent_counts_) {
        sent_counts_ = wanted_counts_;
        cw |= controlword::kNewSetPoint | controlword::kChangeSetImmediately;
        setpoint_ = SetPoint::raised;
      }
      break;
    case SetPoint::raised:
      if (acknowledged) {
        setpoint_ = SetPoint::lowering;
      } else {
        cw |= controlword::kNewSetPoint | controlword::kChangeSetImmediately;
      }
      break;
    case SetPoint::lowering:
      if (!acknowledged) setpoint_ = SetPoint::idle;
      break;
  }
  send_rpdo(cw, out);
}

// Quick stop held; reported once the drive stands still.
void DriveLink::step_quick_stopped(LinkOutput& out) {
  const DriveState ds = decode_statusword(statusword_);
  if (ds == DriveState::quick_stop_active && (statusword_ & statusword::kTargetReached) &&
      !quick_stop_reported_) {
    out.event(config_.node_id, LinkEvent::quick_stopped, 0);
    quick_stop_reported_ = true;
  }
  send_rpdo(controlword::kQuickStop, out);
}

}  // namespace petra::canopen
