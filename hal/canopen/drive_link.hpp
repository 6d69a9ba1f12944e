// The master's view of one CiA 402 drive: boots it (NMT reset, expedited SDO
// configuration, NMT start), enables it (CiA 402 state machine to Operation
// Enabled in profile position mode), feeds it target positions (set-point
// handshake), watches its heartbeat, statusword and emergencies, and records
// the first fault. Protocol logic only: frames go out through a FrameSink and
// come in through on_*(); time is the caller's monotonic milliseconds.
// Memory: fixed-size (the SDO plan is an array of kMaxSdoSteps); no heap.
#pragma once

#include <array>
#include <cstdint>

#include "algo/core/result.hpp"
#include "hal/canopen/cia301.hpp"
#include "hal/canopen/cia402.hpp"

namespace petra::canopen {

// Per drive parameters. Positions on the wire are encoder counts:
// counts = zero_counts + direction * counts_per_rad * angle_rad.
struct DriveConfig {
  std::uint8_t node_id = 1;
  double counts_per_rad = 1048576.0 / (2.0 * 3.141592653589793);  // 2^20 counts per turn
  std::int32_t zero_counts = 0;
  int direction = 1;               // +1 or -1
  double min_position_rad = -3.0;  // written to the drive's software limits (0x607D)
  double max_position_rad = 3.0;
  double profile_velocity_rad_s = 0.6;
  double profile_acceleration_rad_s2 = 1.2;
  double quick_stop_deceleration_rad_s2 = 3.0;
  double following_error_window_rad = 0.05;
  double position_window_rad = 0.0001;  // "target reached" band (0.07 mm at 0.7 m)
  std::uint16_t heartbeat_producer_ms = 100;
  std::uint16_t heartbeat_timeout_ms = 350;  // consumer: a beat missed for this long is a fault
};
Status validate_drive_config(const DriveConfig& config);
// The wire convention: radians to encoder counts and back.
std::int32_t position_to_counts(const DriveConfig& config, double rad);
double counts_to_position(const DriveConfig& config, std::int32_t counts);

// Timing of the master's own procedures (ms).
struct LinkTiming {
  std::uint16_t boot_timeout_ms = 3000;    // reset to boot-up heartbeat
  std::uint16_t sdo_timeout_ms = 200;      // one SDO request to its answer
  std::uint16_t start_timeout_ms = 1000;   // NMT start to "operational" heartbeat
  std::uint16_t enable_timeout_ms = 1000;  // enable request to Operation Enabled
  std::uint8_t master_node_id = 0x7F;      // the master's own heartbeat, watched by the drives
  std::uint16_t master_heartbeat_ms = 100;
  std::uint16_t drive_watches_master_ms = 500;  // drive consumer time for the master's beat
};

enum class LinkState : std::uint8_t {
  idle = 0,           // not booted
  resetting = 1,      // NMT reset communication sent; waiting for the boot-up heartbeat
  configuring = 2,    // SDO plan running
  starting = 3,       // NMT start sent; waiting for an "operational" heartbeat
  operational = 4,    // NMT operational, power stage off (switch on disabled or ready)
  enabling = 5,       // walking the CiA 402 state machine towards Operation Enabled
  ready = 6,          // Operation Enabled, profile position: follows targets
  quick_stopped = 7,  // quick stop commanded: decelerated, holding (option code 6)
  fault = 8,          // see fault(); cleared only by reboot()
};
const char* link_state_name(LinkState state);

enum class DriveFault : std::uint8_t {
  none = 0,
  boot_timeout = 1,       // no boot-up heartbeat after the reset
  sdo_timeout = 2,        // a configuration SDO got no answer (detail: index << 8 | sub)
  sdo_abort = 3,          // the drive refused a configuration SDO (detail: abort code)
  wrong_device = 4,       // device type / supported modes not a CiA 402 profile position drive
  start_timeout = 5,      // no "operational" heartbeat after NMT start
  heartbeat_lost = 6,     // no heartbeat for heartbeat_timeout_ms
  nmt_state = 7,          // heartbeat reports a reboot or a stop we did not ask for
  emergency = 8,          // EMCY received (detail: error code)
  drive_fault = 9,        // statusword shows Fault or Fault Reaction Active
  following_error = 10,   // statusword bit 13 or EMCY 0x8611
  enable_refused = 11,    // no Operation Enabled within enable_timeout_ms
  unexpected_state = 12,  // left Operation Enabled without being asked
};
const char* drive_fault_name(DriveFault fault);

// What happened, for the executive's event log.
enum class LinkEvent : std::uint8_t {
  booted = 0,         // boot-up heartbeat seen
  configured = 1,     // SDO plan done
  operational = 2,    // NMT operational
  enabled = 3,        // Operation Enabled
  fault = 4,          // entered fault (detail: DriveFault << 24 | fault detail & 0xFFFFFF)
  emergency = 5,      // EMCY (detail: error code), also when it is not a fault
  quick_stopped = 6,  // holding after a quick stop
  bad_frame = 7,      // a frame from this node failed validation (detail: COB-ID)
  disabled = 8,       // power stage off on request
  bus_state = 9,      // node 0: the CAN controller changed state (detail: hal::CanBusState)
};
const char* link_event_name(LinkEvent event);

// Where a link sends frames and events (the master).
class LinkOutput {
 public:
  virtual void send(const CanFrame& frame) = 0;
  virtual void event(std::uint8_t node, LinkEvent event, std::uint32_t detail) = 0;

 protected:
  ~LinkOutput() = default;
};

class DriveLink {
 public:
  static constexpr std::size_t kMaxSdoSteps = 32;

  Status configure(const DriveConfig& config, const LinkTiming& timing);

  // Commands (take effect on the next step()).
  void reboot(std::int64_t now_ms, LinkOutput& out);  // NMT reset comm, configure, start
  void enable(std::int64_t now_ms);                   // from operational or quick_stopped
  void quick_stop(LinkOutput& out);                   // from enabling or ready
  void disable(LinkOutput& out);                      // power stage off (disable voltage)
  Status set_target(double position_rad);             // ready only; inside the limits

  // Frames from this node (the master routes by COB-ID; lengths unchecked yet).
  void on_heartbeat(const CanFrame& frame, std::int64_t now_ms, LinkOutput& out);
  void on_sdo(const CanFrame& frame, std::int64_t now_ms, LinkOutput& out);
  void on_tpdo(const CanFrame& frame, std::int64_t now_ms, LinkOutput& out);
  void on_emcy(const CanFrame& frame, LinkOutput& out);

  // Once per control cycle, before the master's SYNC: timeouts, the next SDO,
  // the CiA 402 step and the RPDO.
  void step(std::int64_t now_ms, LinkOutput& out);

  // Status.
  std::uint8_t node_id() const { return config_.node_id; }
  LinkState state() const { return state_; }
  DriveFault fault() const { return fault_; }
  std::uint32_t fault_detail() const { return fault_detail_; }
  DriveState drive_state() const { return decode_statusword(statusword_); }
  std::uint16_t statusword() const { return statusword_; }
  bool has_feedback() const { return have_feedback_; }
  double position_rad() const;  // last TPDO
  double target_rad() const;    // last target given
  bool target_reached() const;  // acknowledged, statusword bit 10, within the window
  std::uint16_t last_emcy_code() const { return last_emcy_; }
  std::int32_t to_counts(double rad) const;
  double to_rad(std::int32_t counts) const;

 private:
  struct SdoStep {
    bool upload = false;
    SdoAddress address;
    std::uint32_t value = 0;
    std::uint8_t size = 4;
  };
  void build_sdo_plan();
  void enter_fault(DriveFault fault, std::uint32_t detail, LinkOutput& out);
  void send_sdo_step(std::int64_t now_ms, LinkOutput& out);
  // step()'s parts.
  void check_heartbeat(std::int64_t now_ms, LinkOutput& out);
  void step_configuring(std::int64_t now_ms, LinkOutput& out);
  void step_enabling(std::int64_t in_state, LinkOutput& out);
  void step_ready(LinkOutput& out);
  void step_quick_stopped(LinkOutput& out);
  Status check_upload(const SdoStep& step, std::uint32_t value);
  void send_rpdo(std::uint16_t controlword, LinkOutput& out);

  DriveConfig config_;
  LinkTiming timing_;
  LinkState state_ = LinkState::idle;
  DriveFault fault_ = DriveFault::none;
  std::uint32_t fault_detail_ = 0;
  std::int64_t state_since_ms_ = 0;
  std::int64_t last_heartbeat_ms_ = 0;
  bool heartbeat_seen_ = false;

  std::array<SdoStep, kMaxSdoSteps> plan_{};
  std::size_t plan_size_ = 0;
  std::size_t plan_next_ = 0;
  bool sdo_pending_ = false;
  std::int64_t sdo_sent_ms_ = 0;
  bool enable_requested_ = false;

  std::uint16_t statusword_ = 0;
  std::int32_t position_counts_ = 0;
  bool have_feedback_ = false;
  std::uint16_t last_emcy_ = 0;

  // Profile position set-point handshake (CiA 402 6.2.2): raise bit 4 with a
  // new target, wait for bit 12, lower bit 4, wait for bit 12 to drop.
  enum class SetPoint : std::uint8_t { idle, raised, lowering };
  SetPoint setpoint_ = SetPoint::idle;
  std::int32_t wanted_counts_ = 0;
  std::int32_t sent_counts_ = 0;
  bool wanted_valid_ = false;
  bool fault_reset_edge_ = false;
  bool quick_stop_reported_ = false;
};

}  // namespace petra::canopen
