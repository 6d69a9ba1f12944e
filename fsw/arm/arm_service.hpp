// The arm service: turns ARM_GOTO / ARM_STOW / ABORT into motion of the five
// CANopen drives and reports what the arm does.
//   goto(plane): plan (IK, joint limits, standoff along the normal, straight
//     approach; algo/arm/arm_trajectory), then stream set-points each cycle:
//     [retreat along the previous normal] -> joint move to the standoff ->
//     straight approach -> settle; finally verify the reached pose from the
//     drives' position feedback (forward kinematics) against the plane.
//   stow: [retreat] -> joint move to the stowed pose.
//   quick_stop: every drive ramps down and holds (ABORT, e-stop, SAFE).
// Any drive fault, lost heartbeat or bus-off stops the arm (the master quick-
// stops the other drives) and leaves the service in `fault` with an event;
// reset() reboots the drives.
// step(now) must run every control cycle, moving or not: it drives the
// CANopen master (heartbeats both ways, SYNC, feedback).
// Memory: fixed-size (the master, three planned segments, an event queue);
// no heap after configure().
#pragma once

#include <array>
#include <cstdint>

#include "algo/arm/arm_trajectory.hpp"
#include "algo/core/fixed_vector.hpp"
#include "hal/can.hpp"
#include "hal/canopen/canopen_master.hpp"

namespace petra::fsw::arm {

using petra::arm::JointVector;

// Two heartbeat producer periods (100 ms): the shortest consumer time allowed.
inline constexpr std::uint16_t kMinHeartbeatTimeoutMs = 200;

struct ArmServiceConfig {
  petra::arm::ArmGeometry geometry = petra::arm::rover_arm_geometry();
  petra::arm::JointLimits limits = petra::arm::default_joint_limits();
  canopen::LinkTiming timing;
  double max_tool_speed_mm_s = 10.0;  // straight approach and retreat
  double max_tool_accel_mm_s2 = 20.0;
  double min_standoff_mm = 5.0;  // ARM_GOTO standoff range (the command allows 0..300)
  double max_standoff_mm = 300.0;
  double reach_tolerance_mm = 1.0;  // verification of the reached pose
  double axis_tolerance_deg = 0.5;
  std::int64_t settle_timeout_ms = 3000;  // last set-point to "target reached"
  // Heartbeat consumer time, both ways (master watching each drive, each drive
  // watching the master); 0 keeps the flight defaults (DriveConfig and
  // LinkTiming: 350 and 500 ms). Tests on a shared host raise it so that a
  // stalled process is not taken for a lost drive.
  std::uint16_t heartbeat_timeout_ms = 0;
};
Status validate_config(const ArmServiceConfig& config);

enum class ArmState : std::uint8_t {
  off = 0,          // drives not booted
  booting = 1,      // NMT reset, SDO configuration, NMT start
  enabling = 2,     // CiA 402 towards Operation Enabled
  holding = 3,      // enabled, still
  moving = 4,       // joint move (to a standoff or to stow)
  approaching = 5,  // straight line to contact
  retreating = 6,   // straight line back out along the normal
  settling = 7,     // a waypoint's last set-point sent; waiting for the drives to arrive
  stopped = 8,      // quick stop: holding where it stopped
  fault = 9,        // a drive or the bus failed; reset() to recover
};
const char* arm_state_name(ArmState state);

enum class MotionProgress : std::uint8_t { idle = 0, moving = 1, reached = 2, failed = 3 };

// A grind plane to reach (world frame): the contact point and the outward normal.
struct ArmGoal {
  Eigen::Vector3d centroid_mm = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  double standoff_mm = 50.0;
};

enum class ArmEventKind : std::uint8_t {
  refused = 0,         // a goto/stow was refused (code: ArmReason, node: joint 1..5)
  started = 1,         // motion started (code 0 goto, 1 stow)
  reached = 2,         // arrived and verified (detail: tip error in um)
  verify_failed = 3,   // arrived but the pose is off (detail: tip error in um)
  settle_timeout = 4,  // the drives did not report "target reached" in time
  drive_fault = 5,     // node, code: DriveFault, detail: EMCY code / abort code / ...
  emergency = 6,       // node, detail: EMCY error code (also when not a fault)
  bus_state = 7,       // code: hal::CanBusState
  bad_frame = 8,       // node, detail: COB-ID
  stopped = 9,         // quick stop commanded
  ready = 10,          // drives booted and enabled
};
const char* arm_event_name(ArmEventKind kind);

struct ArmEvent {
  ArmEventKind kind = ArmEventKind::ready;
  std::uint8_t node = 0;
  std::uint8_t code = 0;
  std::uint32_t detail = 0;
};

// What telemetry reports about the arm (docs/icd.md, arm state).
struct ArmTelemetry {
  ArmState state = ArmState::off;
  MotionProgress progress = MotionProgress::idle;
  std::array<double, 5> joint_rad{};                 // measured (drive feedback)
  std::array<double, 5> joint_target_rad{};          // last set-point
  Eigen::Vector3d tip_mm = Eigen::Vector3d::Zero();  // forward kinematics of the measured joints
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
  petra::arm::ArmReason last_refusal = petra::arm::ArmReason::ok;
  std::uint8_t last_refusal_joint = 0;
  double last_tip_error_mm = 0.0;  // of the last verification
  double last_axis_error_deg = 0.0;
  std::uint8_t fault_node = 0;
  canopen::DriveFault fault = canopen::DriveFault::none;
  std::uint32_t fault_detail = 0;
  std::array<canopen::LinkState, 5> drive_state{};
  hal::CanBusState bus = hal::CanBusState::error_active;
  std::uint32_t moves_completed = 0;
  std::uint32_t events_dropped = 0;
  canopen::MasterCounters can;
};

class ArmService {
 public:
  static constexpr std::size_t kEventCapacity = 32;

  Status configure(const ArmServiceConfig& config, hal::CanPort& port);

  void power_up(std::int64_t now_ms);  // boot and enable the drives
  Status reset(std::int64_t now_ms);   // after a fault: reboot the drives
  Status start_goto(const ArmGoal& goal, std::int64_t now_ms);
  Status start_stow(std::int64_t now_ms);
  void quick_stop();

  // Every control cycle.
  void step(std::int64_t now_ms);

  ArmState state() const { return state_; }
  MotionProgress progress() const;
  ArmTelemetry telemetry() const;
  bool pop_event(ArmEvent& out);
  JointVector measured_joints() const;
  const canopen::CanopenMaster& master() const { return master_; }

 private:
  enum class SegmentKind : std::uint8_t { joint_move, approach, retreat };
  struct Segment {
    SegmentKind kind = SegmentKind::joint_move;
    petra::arm::JointMove move;
    petra::arm::StraightApproach line;
  };
  enum class Goal : std::uint8_t { none, contact, stow };

  Status check_can_start() const;
  Status plan_retreat_if_near_surface(JointVector& from);
  Status begin(Goal goal, std::int64_t now_ms);
  void push_event(ArmEventKind kind, std::uint8_t node, std::uint8_t code, std::uint32_t detail);
  void drain_master_events();
  void run_segment(std::int64_t now_ms);
  void start_next_segment(std::int64_t now_ms);
  void settle(std::int64_t now_ms);
  void enter_fault();
  Status send_targets(const JointVector& q);

  ArmServiceConfig config_;
  canopen::CanopenMaster master_;
  ArmState state_ = ArmState::off;
  Goal goal_ = Goal::none;
  bool failed_ = false;
  bool reached_ = false;
  FixedVector<Segment, 3> segments_;
  std::size_t segment_ = 0;
  std::int64_t segment_start_ms_ = 0;
  std::int64_t settle_start_ms_ = 0;
  JointVector last_target_ = JointVector::Zero();
  JointVector final_target_ = JointVector::Zero();
  ArmGoal contact_goal_;
  // The straight line the tool last moved on (approach done or interrupted):
  // any next motion first backs out along it.
  bool near_surface_ = false;
  ArmGoal surface_goal_;
  bool pending_start_ = false;  // re-enabling after a stop, then start the segments
  bool enable_wanted_ = false;  // cleared by a quick stop during boot

  petra::arm::ArmReason last_refusal_ = petra::arm::ArmReason::ok;
  std::uint8_t last_refusal_joint_ = 0;
  double last_tip_error_mm_ = 0.0;
  double last_axis_error_deg_ = 0.0;
  std::uint32_t moves_completed_ = 0;
  std::uint8_t fault_node_ = 0;

  std::array<ArmEvent, kEventCapacity> events_{};
  std::size_t event_head_ = 0;
  std::size_t event_size_ = 0;
  std::uint32_t events_dropped_ = 0;
};

}  // namespace petra::fsw::arm
