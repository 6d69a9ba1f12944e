#include "fsw/arm/flight_arm.hpp"

#include <cmath>

namespace petra::fsw::arm {

namespace {

std::int32_t i32(std::uint32_t v) {
  return static_cast<std::int32_t>(v > 0x7FFFFFFFu ? 0x7FFFFFFFu : v);
}

}  // namespace

Status FlightArm::init(const ArmServiceConfig& config, hal::CanPort& port,
                       const hal::Clock& clock) {
  PETRA_TRY(service_.configure(config, port));
  clock_ = &clock;
  service_.power_up(now_ms());
  return ok_status();
}

Status FlightArm::start_goto(const ArmTarget& t) {
  ArmGoal goal;
  goal.centroid_mm = Eigen::Vector3d(t.centroid_mm[0], t.centroid_mm[1], t.centroid_mm[2]);
  goal.normal = Eigen::Vector3d(t.normal[0], t.normal[1], t.normal[2]);
  goal.standoff_mm = t.standoff_mm;
  return service_.start_goto(goal, now_ms());
}

Status FlightArm::start_stow() {
  return service_.start_stow(now_ms());
}

ArmProgress FlightArm::poll() {
  service_.step(now_ms());
  switch (service_.progress()) {
    case MotionProgress::moving:
      return ArmProgress::MOVING;
    case MotionProgress::reached:
      return ArmProgress::REACHED;
    case MotionProgress::failed:
      return ArmProgress::FAILED;
    case MotionProgress::idle:
      break;
  }
  return ArmProgress::IDLE;
}

void FlightArm::quick_stop() {
  service_.quick_stop();
}

Status FlightArm::reset() {
  if (service_.state() != ArmState::fault) return ok_status();
  return service_.reset(now_ms());
}

bool FlightArm::pop_event(ArmEventOut& out) {
  ArmEvent e;
  if (!service_.pop_event(e)) return false;
  out = ArmEventOut{};
  const auto node = static_cast<std::int32_t>(e.node);
  const auto code = static_cast<std::int32_t>(e.code);
  switch (e.kind) {
    case ArmEventKind::ready:
      out.id = EventId::ARM_READY;
      out.args = {static_cast<std::int32_t>(service_.master().drive_count()), 0, 0, 0};
      break;
    case ArmEventKind::refused:
      out.id = EventId::ARM_REFUSED;
      out.args = {code, node, i32(e.detail), 0};
      break;
    case ArmEventKind::started:
      out.id = EventId::ARM_MOTION_STARTED;
      out.args = {code, 0, 0, 0};
      break;
    case ArmEventKind::reached:
      out.id = EventId::ARM_REACHED;
      out.args = {code, i32(e.detail), 0, 0};
      break;
    case ArmEventKind::verify_failed:
      out.id = EventId::ARM_VERIFY_FAILED;
      out.args = {code, i32(e.detail), 0, 0};
      break;
    case ArmEventKind::settle_timeout:
      out.id = EventId::ARM_SETTLE_TIMEOUT;
      out.args = {i32(e.detail), 0, 0, 0};
      break;
    case ArmEventKind::drive_fault:
      out.id = EventId::ARM_DRIVE_FAULT;
      out.args = {node, code, i32(e.detail), 0};
      out.safe = true;  // a drive fault or a lost heartbeat: the arm cannot be trusted
      break;
    case ArmEventKind::emergency:
      out.id = EventId::ARM_EMERGENCY;
      out.args = {node, i32(e.detail), 0, 0};
      break;
    case ArmEventKind::bus_state:
      out.id = EventId::ARM_CAN_BUS;
      out.args = {code, 0, 0, 0};
      out.safe = e.code == static_cast<std::uint8_t>(hal::CanBusState::bus_off);
      break;
    case ArmEventKind::bad_frame:
      out.id = EventId::ARM_BAD_FRAME;
      out.args = {node, i32(e.detail), 0, 0};
      break;
    case ArmEventKind::stopped:
      out.id = EventId::ARM_STOPPED;
      break;
  }
  return true;
}

bool FlightArm::status(tlm::ArmStatus& s) const {
  const ArmTelemetry t = service_.telemetry();
  constexpr double kToDeg = 180.0 / 3.141592653589793;
  s.state = static_cast<std::uint8_t>(t.state);
  s.progress = static_cast<std::uint8_t>(t.progress);
  for (std::size_t j = 0; j < 5; ++j) {
    s.joint_deg[j] = static_cast<float>(t.joint_rad[j] * kToDeg);
    s.target_deg[j] = static_cast<float>(t.joint_target_rad[j] * kToDeg);
    s.drive_state[j] = static_cast<std::uint8_t>(t.drive_state[j]);
  }
  for (int k = 0; k < 3; ++k) {
    s.tip_mm[static_cast<std::size_t>(k)] = t.tip_mm[k];
    s.axis[static_cast<std::size_t>(k)] = t.axis[k];
  }
  s.refusal = static_cast<std::uint8_t>(t.last_refusal);
  s.refusal_joint = t.last_refusal_joint;
  s.tip_error_mm = static_cast<float>(t.last_tip_error_mm);
  s.axis_error_deg = static_cast<float>(t.last_axis_error_deg);
  s.fault_node = t.fault_node;
  s.fault = static_cast<std::uint8_t>(t.fault);
  s.fault_detail = t.fault_detail;
  s.bus_state = static_cast<std::uint8_t>(t.bus);
  s.moves_completed = t.moves_completed;
  s.can_sent = t.can.frames_sent;
  s.can_received = t.can.frames_received;
  s.can_bad_frames = t.can.bad_frames;
  s.can_send_errors = t.can.send_errors;
  return true;
}

}  // namespace petra::fsw::arm
