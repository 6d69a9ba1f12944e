#include "sim/arm/sim_drive.hpp"

#include <algorithm>
#include <cmath>

namespace petra::sim {

using namespace canopen;

namespace {

constexpr double kStepS = 0.001;  // motion integration step

// Objects a PDO may carry, with their bit length, and the direction.
bool mappable(std::uint32_t entry, bool receive) {
  if (receive) return entry == od::kMapControlword || entry == od::kMapTargetPosition;
  return entry == od::kMapStatusword || entry == od::kMapPositionActual;
}

}  // namespace

SimDrive::SimDrive(const SimDriveParams& params) : p_(params) {
  reset_communication();
  reset_application();
  actual_ = demand_ = params.initial_position_counts;
  target_ = params.initial_position_counts;
}

void SimDrive::power_on(std::int64_t now_ms) {
  powered_ = true;
  now_ms_ = now_ms;
  nmt_ = NmtState::boot_up;
  boot_at_ms_ = now_ms + p_.boot_delay_ms;
  reset_communication();
  reset_application();
}

void SimDrive::power_off() {
  powered_ = false;
  state_ = DriveState::not_ready_to_switch_on;
}

void SimDrive::reset_communication() {
  heartbeat_ms_ = 0;
  consumer_ = 0;
  master_seen_ms_ = -1;
  // Power-on PDO layout: controlword in, statusword out (Petra must remap).
  rpdo_ = Mapping{cob_id(Function::rpdo1, p_.node_id), 0xFF, 1, {od::kMapControlword, 0, 0, 0}};
  tpdo_ = Mapping{cob_id(Function::tpdo1, p_.node_id), 0xFF, 1, {od::kMapStatusword, 0, 0, 0}};
}

void SimDrive::reset_application() {
  state_ = DriveState::switch_on_disabled;
  controlword_ = 0;
  quick_stop_option_ = 2;
  mode_ = 0;
  error_register_ = 0;
  following_error_ = false;
  following_for_s_ = 0.0;
  internal_limit_ = false;
  setpoint_ack_ = false;
  demand_ = actual_;
  velocity_ = 0.0;
  target_ = static_cast<std::int32_t>(std::lround(actual_));
  pending_target_ = target_;
}

std::uint16_t SimDrive::statusword() const {
  std::uint16_t sw = statusword_bits(state_);
  const bool powered_stage = state_ == DriveState::switched_on ||
                             state_ == DriveState::operation_enabled ||
                             state_ == DriveState::quick_stop_active;
  if (powered_stage) sw |= statusword::kVoltageEnabled;
  sw |= statusword::kRemote;
  if (state_ == DriveState::operation_enabled) {
    if (demand_ == target_ && velocity_ == 0.0 && std::abs(target_ - actual_) <= position_window_) {
      sw |= statusword::kTargetReached;
    }
  } else if (state_ == DriveState::quick_stop_active && velocity_ == 0.0) {
    sw |= statusword::kTargetReached;
  }
  if (internal_limit_) sw |= statusword::kInternalLimit;
  if (setpoint_ack_) sw |= statusword::kSetPointAcknowledge;
  if (following_error_) sw |= statusword::kFollowingError;
  return sw;
}

void SimDrive::on_frame(const hal::CanFrame& f, std::int64_t now_ms, FrameSink& out) {
  if (!powered_ || nmt_ == NmtState::boot_up || f.extended || f.rtr) return;
  const std::uint8_t n = p_.node_id;
  if (f.id == 0x000) {
    handle_nmt(f, now_ms);
  } else if (f.id == 0x080) {
    if (nmt_ == NmtState::operational && (tpdo_.cob_id & od::kPdoDisabled) == 0 &&
        tpdo_.type >= 1 && tpdo_.type <= 240) {
      send_tpdo(out);
    }
  } else if (f.id == cob_id(Function::sdo_rx, n)) {
    if (nmt_ == NmtState::preoperational || nmt_ == NmtState::operational) handle_sdo(f, out);
  } else if ((rpdo_.cob_id & od::kPdoDisabled) == 0 && f.id == (rpdo_.cob_id & 0x7FF)) {
    if (nmt_ == NmtState::operational) handle_rpdo(f, out);
  } else if (consumer_ != 0 &&
             f.id == cob_id(Function::heartbeat, static_cast<std::uint8_t>(consumer_ >> 16))) {
    master_seen_ms_ = now_ms;
  }
}

void SimDrive::handle_nmt(const hal::CanFrame& f, std::int64_t now_ms) {
  std::uint8_t node = 0;
  auto cmd = parse_nmt(f, node);
  if (!cmd || (node != 0 && node != p_.node_id)) return;
  switch (*cmd) {
    case NmtCommand::start:
      nmt_ = NmtState::operational;
      break;
    case NmtCommand::stop:
      nmt_ = NmtState::stopped;
      break;
    case NmtCommand::enter_preoperational:
      nmt_ = NmtState::preoperational;
      break;
    case NmtCommand::reset_node:
      reset_application();
      [[fallthrough]];
    case NmtCommand::reset_communication:
      reset_communication();
      nmt_ = NmtState::boot_up;
      boot_at_ms_ = now_ms + p_.boot_delay_ms;
      break;
  }
}

void SimDrive::handle_sdo(const hal::CanFrame& f, FrameSink& out) {
  auto req = parse_sdo(f, false);
  SdoMessage reply;
  if (!req) {
    reply.kind = SdoKind::abort;
    reply.address.index = static_cast<std::uint16_t>(f.data[1] | (f.data[2] << 8));
    reply.address.subindex = f.data[3];
    reply.value = sdo_abort::kBadCommand;
  } else {
    reply.address = req->address;
    std::uint32_t abort = 0;
    if (req->kind == SdoKind::download_request) {
      abort = write_object(req->address, req->value, req->size);
      reply.kind = SdoKind::download_response;
    } else {
      std::uint32_t value = 0;
      abort = read_object(req->address, value);
      reply.kind = SdoKind::upload_response;
      reply.value = value;
      reply.size = 4;
    }
    if (abort != 0) {
      reply.kind = SdoKind::abort;
      reply.value = abort;
    }
  }
  if (reply.kind == SdoKind::abort) ++sdo_aborts_;
  out.send(make_sdo_response(p_.node_id, reply));
  if (sdo_controlword_pending_) {
    sdo_controlword_pending_ = false;
    apply_controlword(sdo_controlword_, out);
  }
}

std::uint32_t SimDrive::read_object(SdoAddress a, std::uint32_t& v) const {
  auto map_entry = [](const Mapping& m, std::uint8_t sub, std::uint32_t& value) -> std::uint32_t {
    if (sub == 0) {
      value = m.count;
      return 0;
    }
    if (sub > 4) return sdo_abort::kNoSubindex;
    value = m.entries[sub - 1];
    return 0;
  };
  switch (a.index) {
    case 0x1000:
      v = p_.device_type;
      return 0;
    case 0x1001:
      v = error_register_;
      return 0;
    case 0x1016:
      v = a.subindex == 0 ? 1 : consumer_;
      return a.subindex <= 1 ? 0 : sdo_abort::kNoSubindex;
    case 0x1017:
      v = heartbeat_ms_;
      return 0;
    case 0x1400:
      v = a.subindex == 1 ? rpdo_.cob_id : rpdo_.type;
      return 0;
    case 0x1800:
      v = a.subindex == 1 ? tpdo_.cob_id : tpdo_.type;
      return 0;
    case 0x1600:
      return map_entry(rpdo_, a.subindex, v);
    case 0x1A00:
      return map_entry(tpdo_, a.subindex, v);
    case 0x6040:
      v = controlword_;
      return 0;
    case 0x6041:
      v = statusword();
      return 0;
    case 0x605A:
      v = static_cast<std::uint16_t>(quick_stop_option_);
      return 0;
    case 0x6060:
      v = static_cast<std::uint8_t>(mode_);
      return 0;
    case 0x6061:
      v = static_cast<std::uint8_t>(mode_);
      return 0;
    case 0x6064:
      v = static_cast<std::uint32_t>(static_cast<std::int32_t>(std::lround(actual_)));
      return 0;
    case 0x6065:
      v = following_window_;
      return 0;
    case 0x6066:
      v = following_timeout_ms_;
      return 0;
    case 0x6067:
      v = position_window_;
      return 0;
    case 0x607A:
      v = static_cast<std::uint32_t>(pending_target_);
      return 0;
    case 0x607D:
      v = static_cast<std::uint32_t>(a.subindex == 1 ? limit_min_ : limit_max_);
      return 0;
    case 0x6081:
      v = profile_velocity_;
      return 0;
    case 0x6083:
      v = profile_acceleration_;
      return 0;
    case 0x6084:
      v = profile_deceleration_;
      return 0;
    case 0x6085:
      v = quick_stop_deceleration_;
      return 0;
    case 0x6502:
      v = p_.supported_modes;
      return 0;
    default:
      return sdo_abort::kNoObject;
  }
}

std::uint32_t SimDrive::write_mapping(Mapping& m, bool receive, std::uint8_t sub,
                                      std::uint32_t value) {
  // CiA 301: the mapping may change only while the PDO is disabled and, for the
  // entries, while the count is 0.
  if ((m.cob_id & od::kPdoDisabled) == 0) return sdo_abort::kDeviceState;
  if (sub == 0) {
    if (value > 4) return sdo_abort::kCannotMap;
    unsigned bits = 0;
    for (std::uint32_t i = 0; i < value; ++i) {
      if (!mappable(m.entries[i], receive)) return sdo_abort::kCannotMap;
      bits += m.entries[i] & 0xFF;
    }
    if (bits > 64) return sdo_abort::kCannotMap;
    m.count = static_cast<std::uint8_t>(value);
    return 0;
  }
  if (sub > 4) return sdo_abort::kNoSubindex;
  if (m.count != 0) return sdo_abort::kDeviceState;
  if (!mappable(value, receive)) return sdo_abort::kCannotMap;
  m.entries[sub - 1] = value;
  return 0;
}

std::uint32_t SimDrive::write_object(SdoAddress a, std::uint32_t v, std::uint8_t size) {
  // Object sizes in bytes; a download that states another size is refused.
  auto sized = [&](std::uint8_t want) -> bool { return size == 0 || size == want; };
  const std::uint8_t sub = a.subindex;
  switch (a.index) {
    case 0x1000:
    case 0x1001:
    case 0x6041:
    case 0x6061:
    case 0x6064:
    case 0x6502:
      return sdo_abort::kReadOnly;
    case 0x1016:
      if (sub != 1) return sub == 0 ? sdo_abort::kReadOnly : sdo_abort::kNoSubindex;
      if (!sized(4)) return sdo_abort::kLengthMismatch;
      consumer_ = v;
      master_seen_ms_ = -1;
      return 0;
    case 0x1017:
      if (!sized(2)) return sdo_abort::kLengthMismatch;
      heartbeat_ms_ = static_cast<std::uint16_t>(v);
      return 0;
    case 0x1400:
    case 0x1800: {
      Mapping& m = a.index == 0x1400 ? rpdo_ : tpdo_;
      if (sub == 1) {
        if (!sized(4)) return sdo_abort::kLengthMismatch;
        // Only the predefined COB-ID may be used; bit 31 enables/disables.
        const std::uint32_t base =
            cob_id(a.index == 0x1400 ? Function::rpdo1 : Function::tpdo1, p_.node_id);
        if ((v & 0x7FFFFFFF) != base) return sdo_abort::kValueRange;
        m.cob_id = v;
        return 0;
      }
      if (sub == 2) {
        if (!sized(1)) return sdo_abort::kLengthMismatch;
        m.type = static_cast<std::uint8_t>(v);
        return 0;
      }
      return sdo_abort::kNoSubindex;
    }
    case 0x1600:
    case 0x1A00:
      if (!sized(sub == 0 ? 1 : 4)) return sdo_abort::kLengthMismatch;
      return write_mapping(a.index == 0x1600 ? rpdo_ : tpdo_, a.index == 0x1600, sub, v);
    case 0x6040:
      if (!sized(2)) return sdo_abort::kLengthMismatch;
      sdo_controlword_ = static_cast<std::uint16_t>(v);
      sdo_controlword_pending_ = true;
      return 0;
    case 0x605A:
      if (!sized(2)) return sdo_abort::kLengthMismatch;
      quick_stop_option_ = static_cast<std::int16_t>(v);
      return 0;
    case 0x6060:
      if (!sized(1)) return sdo_abort::kLengthMismatch;
      if (static_cast<std::int8_t>(v) != kModeProfilePosition) return sdo_abort::kValueRange;
      mode_ = static_cast<std::int8_t>(v);
      return 0;
    case 0x6065:
      following_window_ = v;
      return sized(4) ? 0 : sdo_abort::kLengthMismatch;
    case 0x6066:
      following_timeout_ms_ = static_cast<std::uint16_t>(v);
      return sized(2) ? 0 : sdo_abort::kLengthMismatch;
    case 0x6067:
      position_window_ = v;
      return sized(4) ? 0 : sdo_abort::kLengthMismatch;
    case 0x607A:
      if (!sized(4)) return sdo_abort::kLengthMismatch;
      pending_target_ = static_cast<std::int32_t>(v);
      return 0;
    case 0x607D:
      if (!sized(4)) return sdo_abort::kLengthMismatch;
      if (sub == 1)
        limit_min_ = static_cast<std::int32_t>(v);
      else if (sub == 2)
        limit_max_ = static_cast<std::int32_t>(v);
      else
        return sdo_abort::kNoSubindex;
      return 0;
    case 0x6081:
    case 0x6083:
    case 0x6084:
    case 0x6085: {
      if (!sized(4)) return sdo_abort::kLengthMismatch;
      if (v == 0) return sdo_abort::kValueRange;
      std::uint32_t& field = a.index == 0x6081   ? profile_velocity_
                             : a.index == 0x6083 ? profile_acceleration_
                             : a.index == 0x6084 ? profile_deceleration_
                                                 : quick_stop_deceleration_;
      field = v;
      return 0;
    }
    default:
      return sdo_abort::kNoObject;
  }
}

void SimDrive::handle_rpdo(const hal::CanFrame& f, FrameSink& out) {
  unsigned bytes = 0;
  for (std::uint8_t i = 0; i < rpdo_.count; ++i) bytes += (rpdo_.entries[i] & 0xFF) / 8;
  if (f.len != bytes) return;  // a PDO of the wrong length is not processed
  unsigned at = 0;
  std::uint16_t cw = controlword_;
  for (std::uint8_t i = 0; i < rpdo_.count; ++i) {
    const std::uint32_t e = rpdo_.entries[i];
    const unsigned n = (e & 0xFF) / 8;
    std::uint32_t v = 0;
    for (unsigned k = 0; k < n; ++k) v |= static_cast<std::uint32_t>(f.data[at + k]) << (8 * k);
    at += n;
    if (e == od::kMapControlword) cw = static_cast<std::uint16_t>(v);
    if (e == od::kMapTargetPosition) pending_target_ = static_cast<std::int32_t>(v);
  }
  // The target first, so that a new set-point edge in the same PDO uses it.
  apply_controlword(cw, out);
}

void SimDrive::send_tpdo(FrameSink& out) {
  hal::CanFrame f;
  f.id = tpdo_.cob_id & 0x7FF;
  for (std::uint8_t i = 0; i < tpdo_.count; ++i) {
    const std::uint32_t e = tpdo_.entries[i];
    std::uint32_t v = 0;
    if (e == od::kMapStatusword) v = statusword();
    if (e == od::kMapPositionActual)
      v = static_cast<std::uint32_t>(static_cast<std::int32_t>(std::lround(actual_)));
    const unsigned n = (e & 0xFF) / 8;
    for (unsigned k = 0; k < n; ++k) f.data[f.len++] = static_cast<std::uint8_t>(v >> (8 * k));
  }
  out.send(f);
}

void SimDrive::apply_controlword(std::uint16_t cw, FrameSink& out) {
  const std::uint16_t prev = controlword_;
  controlword_ = cw;
  const bool reset_edge = (cw & controlword::kFaultReset) && !(prev & controlword::kFaultReset);
  if (reset_edge && state_ == DriveState::fault) {
    state_ = DriveState::switch_on_disabled;
    following_error_ = false;
    following_for_s_ = 0.0;
    error_register_ = 0;
    out.send(make_emcy(p_.node_id, Emergency{emcy_code::kNoError, 0, {}}));
    return;
  }
  const DriveCommand cmd = decode_controlword(cw);
  if (cmd != DriveCommand::fault_reset) {
    DriveState next = next_drive_state(state_, cmd, quick_stop_option_);
    if (next == DriveState::operation_enabled && state_ != DriveState::operation_enabled &&
        refuse_enable_) {
      next = state_;  // injected: the power stage will not enable
    }
    if (next == DriveState::operation_enabled && state_ != DriveState::operation_enabled &&
        state_ != DriveState::quick_stop_active) {
      demand_ = actual_;
      velocity_ = 0.0;
      target_ = static_cast<std::int32_t>(std::lround(actual_));
    }
    if (next != DriveState::operation_enabled && next != DriveState::quick_stop_active)
      velocity_ = 0.0;
    state_ = next;
  }
  // Profile position set-point handshake (bit 4 rising edge, bit 12 echoes).
  const bool new_setpoint = (cw & controlword::kNewSetPoint) && !(prev & controlword::kNewSetPoint);
  if (state_ == DriveState::operation_enabled && mode_ == kModeProfilePosition && new_setpoint) {
    std::int64_t t = pending_target_;
    if (cw & controlword::kRelative) t += target_;
    internal_limit_ = t < limit_min_ || t > limit_max_;
    target_ = static_cast<std::int32_t>(std::clamp<std::int64_t>(t, limit_min_, limit_max_));
    setpoint_ack_ = true;
  }
  if (!(cw & controlword::kNewSetPoint)) setpoint_ack_ = false;
}

void SimDrive::enter_fault(std::uint16_t code, FrameSink& out) {
  state_ = DriveState::fault;
  error_register_ = 0x01;
  velocity_ = 0.0;
  demand_ = actual_;
  out.send(make_emcy(p_.node_id, Emergency{code, error_register_, {}}));
}

void SimDrive::inject_fault(std::uint16_t code, FrameSink& out) {
  if (powered_) enter_fault(code, out);
}

void SimDrive::integrate(double dt, FrameSink& out) {
  const bool profile_runs =
      state_ == DriveState::operation_enabled || state_ == DriveState::quick_stop_active;
  if (!profile_runs) {
    demand_ = actual_;  // power stage off: the brake holds the joint where it is
    velocity_ = 0.0;
    return;
  }
  if (state_ == DriveState::operation_enabled) {
    const double d = target_ - demand_;
    const double dec = profile_deceleration_;
    const double v_stop = std::sqrt(2.0 * dec * std::abs(d));
    const double v_want = std::copysign(std::min<double>(profile_velocity_, v_stop), d);
    const bool speeding_up = std::abs(v_want) > std::abs(velocity_) && v_want * velocity_ >= 0.0;
    const double rate = speeding_up ? profile_acceleration_ : dec;
    velocity_ += std::clamp(v_want - velocity_, -rate * dt, rate * dt);
    demand_ += velocity_ * dt;
    // Arrived: within one step's travel at the lowest speed, and slow.
    if (std::abs(target_ - demand_) <= 0.5 * rate * dt * dt + 0.5 &&
        std::abs(velocity_) <= rate * dt) {
      demand_ = target_;
      velocity_ = 0.0;
    }
  } else {
    const double q = quick_stop_deceleration_;
    if (std::abs(velocity_) <= q * dt) {
      velocity_ = 0.0;
      // Options 5..8 hold in Quick Stop Active; the others end switched off.
      if (quick_stop_option_ < 5 || quick_stop_option_ > 8) state_ = DriveState::switch_on_disabled;
    } else {
      velocity_ -= std::copysign(q * dt, velocity_);
    }
    demand_ += velocity_ * dt;
    target_ = static_cast<std::int32_t>(std::lround(demand_));
  }
  if (!stalled_) actual_ += (demand_ - actual_) * std::min(1.0, dt / p_.motor_time_constant_s);
  if (state_ == DriveState::operation_enabled && std::abs(demand_ - actual_) > following_window_) {
    following_for_s_ += dt;
    if (following_for_s_ * 1000.0 > following_timeout_ms_) {
      following_error_ = true;
      enter_fault(emcy_code::kFollowingError, out);
    }
  } else {
    following_for_s_ = 0.0;
  }
}

void SimDrive::step(std::int64_t now_ms, FrameSink& out) {
  if (!powered_) return;
  const std::int64_t elapsed = std::clamp<std::int64_t>(now_ms - now_ms_, 0, 1000);
  now_ms_ = now_ms;
  for (std::int64_t k = 0; k < elapsed; ++k) integrate(kStepS, out);
  if (boot_at_ms_ >= 0 && now_ms >= boot_at_ms_) {
    boot_at_ms_ = -1;
    out.send(make_heartbeat(p_.node_id, NmtState::boot_up));
    nmt_ = NmtState::preoperational;
    last_heartbeat_ms_ = now_ms;
  }
  if (nmt_ != NmtState::boot_up && heartbeat_ms_ > 0 && !heartbeat_stopped_ &&
      now_ms - last_heartbeat_ms_ >= heartbeat_ms_) {
    out.send(make_heartbeat(p_.node_id, nmt_));
    last_heartbeat_ms_ = now_ms;
  }
  // Heartbeat consumer: losing the master while powered is a fault (CiA 301 0x8130).
  const std::uint16_t watch_ms = static_cast<std::uint16_t>(consumer_ & 0xFFFF);
  if (watch_ms > 0 && master_seen_ms_ >= 0 && now_ms - master_seen_ms_ > watch_ms) {
    master_seen_ms_ = -1;
    if (state_ == DriveState::operation_enabled || state_ == DriveState::quick_stop_active) {
      enter_fault(emcy_code::kHeartbeatConsumer, out);
    }
  }
}

}  // namespace petra::sim
