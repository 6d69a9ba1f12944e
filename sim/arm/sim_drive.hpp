// A simulated CiA 402 servo drive node (one per arm joint): the slave side of
// the protocol the master speaks (hal/canopen), on any CanPort.
//   CiA 301: boot-up and heartbeat producer (0x1017), NMT, expedited SDO server
//     over a small object dictionary (docs/arm.md lists it), RPDO1/TPDO1 with
//     mapping programmable as CiA 301 prescribes, TPDO on SYNC, EMCY, and a
//     heartbeat consumer watching the master (0x1016).
//   CiA 402: the power state machine, profile position mode with the set-point
//     handshake, quick stop (option code 0x605A), software position limits.
//   Motion: a trapezoidal profile generator (profile velocity, acceleration,
//     deceleration) feeding a motor that follows with a first-order lag; a
//     following error beyond 0x6065 for longer than 0x6066 faults the drive.
//   Fault injection: heartbeat stops, EMCY with a fault, stall (following
//     error), refusal to enable, power loss.
// Ground code (sim/): no heap use anyway; time is the caller's milliseconds.
#pragma once

#include <array>
#include <cstdint>

#include "hal/canopen/cia301.hpp"
#include "hal/canopen/cia402.hpp"

namespace petra::sim {

struct SimDriveParams {
  std::uint8_t node_id = 1;
  std::int32_t initial_position_counts = 0;
  std::uint16_t boot_delay_ms = 20;     // power-on or reset to the boot-up message
  double motor_time_constant_s = 0.02;  // lag of the motor behind the profile
  std::uint32_t device_type = canopen::od::kDeviceTypeServo;
  std::uint32_t supported_modes = canopen::od::kSupportsProfilePosition;
};

// Frames the drive sends go here (the simulated bus).
class FrameSink {
 public:
  virtual void send(const hal::CanFrame& frame) = 0;

 protected:
  ~FrameSink() = default;
};

class SimDrive {
 public:
  SimDrive() : SimDrive(SimDriveParams{}) {}
  explicit SimDrive(const SimDriveParams& params);

  void power_on(std::int64_t now_ms);
  void power_off();  // silent: no frames at all, as a drive whose supply failed
  bool powered() const { return powered_; }

  // Every frame on the bus (the drive picks what is addressed to it).
  void on_frame(const hal::CanFrame& frame, std::int64_t now_ms, FrameSink& out);
  // Advances motion and timers to now_ms; sends heartbeats and boot-up.
  void step(std::int64_t now_ms, FrameSink& out);

  // Fault injection.
  void stop_heartbeat(bool stopped) { heartbeat_stopped_ = stopped; }
  void refuse_enable(bool refuse) { refuse_enable_ = refuse; }
  void stall(bool stalled) { stalled_ = stalled; }  // motor stops following: following error
  void inject_fault(std::uint16_t emcy_code, FrameSink& out);  // EMCY + Fault

  // What an observer on the test bench sees.
  std::uint8_t node_id() const { return p_.node_id; }
  canopen::NmtState nmt_state() const { return nmt_; }
  canopen::DriveState drive_state() const { return state_; }
  std::uint16_t statusword() const;
  double position_counts() const { return actual_; }
  double demand_counts() const { return demand_; }
  std::int32_t target_counts() const { return target_; }
  std::uint32_t sdo_aborts_sent() const { return sdo_aborts_; }

 private:
  struct Mapping {
    std::uint32_t cob_id = 0;  // bit 31: disabled
    std::uint8_t type = 0xFF;
    std::uint8_t count = 0;
    std::array<std::uint32_t, 4> entries{};
  };
  void reset_communication();
  void reset_application();
  void handle_nmt(const hal::CanFrame& frame, std::int64_t now_ms);
  void handle_sdo(const hal::CanFrame& frame, FrameSink& out);
  void handle_rpdo(const hal::CanFrame& frame, FrameSink& out);
  void send_tpdo(FrameSink& out);
  void apply_controlword(std::uint16_t cw, FrameSink& out);
  // SDO object access: 0 or an abort code.
  std::uint32_t read_object(canopen::SdoAddress a, std::uint32_t& value) const;
  std::uint32_t write_object(canopen::SdoAddress a, std::uint32_t value, std::uint8_t size);
  std::uint32_t write_mapping(Mapping& m, bool receive, std::uint8_t sub, std::uint32_t value);
  void integrate(double dt_s, FrameSink& out);
  void enter_fault(std::uint16_t emcy_code, FrameSink& out);

  SimDriveParams p_;
  bool powered_ = false;
  std::int64_t now_ms_ = 0;
  std::int64_t boot_at_ms_ = -1;  // pending boot-up message
  std::int64_t last_heartbeat_ms_ = 0;
  canopen::NmtState nmt_ = canopen::NmtState::boot_up;

  // Communication objects (0x1000-0x1FFF).
  std::uint16_t heartbeat_ms_ = 0;
  std::uint32_t consumer_ = 0;  // 0x1016:01 (node << 16) | ms
  std::int64_t master_seen_ms_ = -1;
  Mapping rpdo_, tpdo_;
  std::uint8_t error_register_ = 0;

  // CiA 402 objects.
  canopen::DriveState state_ = canopen::DriveState::switch_on_disabled;
  std::uint16_t controlword_ = 0;
  std::int16_t quick_stop_option_ = 2;
  std::int8_t mode_ = 0;
  std::uint32_t following_window_ = 100000;
  std::uint16_t following_timeout_ms_ = 50;
  std::uint32_t position_window_ = 100;
  std::int32_t limit_min_ = -2000000000;
  std::int32_t limit_max_ = 2000000000;
  std::uint32_t profile_velocity_ = 100000;
  std::uint32_t profile_acceleration_ = 200000;
  std::uint32_t profile_deceleration_ = 200000;
  std::uint32_t quick_stop_deceleration_ = 500000;

  // Motion (counts, counts/s).
  std::int32_t target_ = 0;          // the profile's goal
  std::int32_t pending_target_ = 0;  // 0x607A as last written, taken on a new set-point
  std::uint16_t sdo_controlword_ = 0;
  bool sdo_controlword_pending_ = false;
  double demand_ = 0.0;    // profile generator output
  double velocity_ = 0.0;  // of the demand
  double actual_ = 0.0;    // motor
  bool setpoint_ack_ = false;
  bool internal_limit_ = false;
  bool following_error_ = false;
  double following_for_s_ = 0.0;

  bool heartbeat_stopped_ = false;
  bool refuse_enable_ = false;
  bool stalled_ = false;
  std::uint32_t sdo_aborts_ = 0;
};

}  // namespace petra::sim
