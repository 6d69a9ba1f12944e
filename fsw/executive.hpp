// Executive: the flight loop, a rate-group table and a thin command router
// (fsw/dispatcher.cpp) in front of two services it knows by their ports: the
// evaluation (EvaluationPort, fsw/evaluation_service) and the arm (ArmPort).
// init() loads everything and allocates every buffer from the configured
// budget; after it, run_cycle() runs the due rate groups of one minor frame
// and allocates nothing:
//   uplink (every cycle)      receive, validate, acknowledge, dispatch commands
//   pipeline (every cycle)    poll the evaluation: its result, its timeout
//   arm (every cycle)         poll a running arm motion
//   products (every cycle)    queue product chunks while the downlink has room
//   housekeeping (HK_PERIOD_MS)  one HK packet
//   health (health_period_ms) heartbeats; a silent component means SAFE
//   downlink (every cycle)    send queued telemetry without blocking
// Components: ModeManager, EventLog, ParamTable, Health, EvaluationService,
// ProductStreamer, TlmQueue; devices come in through Dependencies.
#pragma once

#include <csignal>
#include <cstdint>
#include <memory>

#include "algo/camera/camera_model.hpp"
#include "cmd/auth.hpp"
#include "cmd/counter_store.hpp"
#include "cmd/validator.hpp"
#include "fsw/arm_port.hpp"
#include "fsw/config.hpp"
#include "fsw/evaluation_service.hpp"
#include "fsw/event_log.hpp"
#include "fsw/executive_counters.hpp"
#include "fsw/health.hpp"
#include "fsw/mode_manager.hpp"
#include "fsw/param_table.hpp"
#include "fsw/product_streamer.hpp"
#include "fsw/rejection_throttle.hpp"
#include "hal/clock.hpp"
#include "hal/digital_input.hpp"
#include "hal/stereo_camera.hpp"
#include "hal/udp_link.hpp"
#include "hal/watchdog.hpp"
#include "tlm/tlm_queue.hpp"

namespace petra::fsw {

struct Dependencies {
  hal::StereoCamera* camera = nullptr;  // required
  const hal::Clock* clock = nullptr;    // required
  PipelineJob* job = nullptr;           // optional: without it EVALUATE fails NO_PIPELINE
  ArmPort* arm = nullptr;               // optional: without it arm commands fail ARM_UNAVAILABLE
  hal::DigitalInput* estop = nullptr;   // optional: asserted = arm quick stop and SAFE
};

class Executive {
 public:
  // Acquisitions tried per pair before the command fails (docs/hal.md "Faults").
  static constexpr int kCameraAttempts = 3;

  Executive() = default;
  ~Executive();
  Executive(const Executive&) = delete;
  Executive& operator=(const Executive&) = delete;

  Status init(const FswConfig& config, const Dependencies& deps);
  void run_cycle();
  // Cycles at the configured period until *stop is non-zero.
  void run(const volatile std::sig_atomic_t* stop);
  void shutdown();

  Mode mode() const { return modes_.mode(); }
  const CommandCounters& command_counters() const { return cmd_; }
  const LoopCounters& loop_counters() const { return loop_; }
  const EventLog& events() const { return events_; }
  const ParamTable& params() const { return params_; }
  const tlm::TlmQueue& downlink_queue() const { return queue_; }
  std::size_t memory_bytes() const { return memory_bytes_; }
  std::uint16_t command_port() const { return uplink_.local_port(); }
  unsigned watchdog_kicks() const { return watchdog_.kicks(); }
  bool evaluation_running() const { return evaluation_.status().running; }

 private:
  struct RateGroup {
    Component component;
    void (Executive::*run)();
    std::uint32_t period_cycles;
  };
  struct Pending {  // an accepted command still running
    bool active = false;
    std::uint8_t function_code = 0;
    std::uint32_t counter = 0;
  };
  Status allocate(const FswConfig& config, const JobBudget& pb, std::size_t arena_bytes);
  Status open_counter();
  void store_counter(std::uint32_t counter);
  void reserve_counters(std::uint32_t count);
  cmd::ValidationContext validation_context() const;
  void update_periods();

  // Rate groups.
  void service_uplink();
  void report_uplink_losses();
  void poll_pipeline();
  void poll_arm();
  void pump_products();
  void send_housekeeping();
  void check_health();
  void flush_downlink();

  // Command handling (fsw/dispatcher.cpp).
  void handle_datagram(std::span<const std::uint8_t> datagram);
  void dispatch(const cmd::Command& c);
  void ack(std::uint8_t fc, std::uint32_t counter, AckStage stage, Reason reason,
           std::uint16_t detail);
  void complete(std::uint8_t fc, std::uint32_t counter);
  void fail(std::uint8_t fc, std::uint32_t counter, Reason reason);
  void handler_rejects(const cmd::Command& c, Reason reason, std::uint16_t detail);
  void on_set_param(const cmd::Command& c);
  void on_acquire(const cmd::Command& c);
  bool enter_evaluate(const cmd::Command& c, bool acquire, std::uint32_t& acquire_us);
  void on_evaluate(const cmd::Command& c);
  void on_propose(const cmd::Command& c);
  void on_select_proposal(const cmd::Command& c);
  cmd::SelectionRefusal pick_refusal(const cmd::Command& c) const;
  ::petra::arm::JointVector arm_pose() const;
  void on_arm(const cmd::Command& c);
  struct ProposalTarget {
    const GrindPlane* plane = nullptr;
    float standoff_mm = 0;
  };
  ProposalTarget proposal_target(const cmd::Command& c) const;
  void on_abort(const cmd::Command& c);
  void on_set_mode(const cmd::Command& c);
  Result<std::uint32_t> acquire_pair();  // the acquisition time, us
  void send_param(std::uint16_t id);
  void stop_activity(Reason why);
  void enter_safe();
  tlm::TmTime now_tm() const;

  FswConfig config_{};
  Dependencies deps_{};
  cmd::AuthKey key_{};
  StereoRig rig_{};
  bool has_rig_ = false;

  ModeManager modes_;
  EventLog events_;
  ParamTable params_;
  Health health_;
  EvaluationService evaluation_;
  ProductStreamer products_;
  tlm::TlmQueue queue_;
  hal::UdpLink uplink_;
  hal::UdpLink downlink_;
  hal::LinuxWatchdog watchdog_;
  cmd::CounterStore counter_store_;
  RejectionThrottle throttle_;

  std::unique_ptr<std::byte[]> memory_;  // every buffer, allocated once in init()
  std::size_t memory_bytes_ = 0;
  Gray8View left_;
  Gray8View right_;
  std::span<std::uint8_t> rx_;       // commands_per_cycle slots of kMaxCommandBytes + 1
  std::span<std::size_t> rx_sizes_;  // the datagram size in each slot
  bool has_frame_ = false;
  std::uint32_t frame_seq_ = 0;

  std::array<RateGroup, 7> groups_{};
  std::array<std::int64_t, kComponentCount> heartbeat_timeout_ns_{};
  CommandCounters cmd_;
  LoopCounters loop_;
  Pending pending_eval_;
  Pending pending_arm_;
  std::int64_t boot_ns_ = 0;
  std::int64_t last_overrun_event_ns_ = 0;
  bool counter_store_failed_ = false;
  std::int64_t previous_key_counter_ = -1;  // >= 0: re-keyed at init (UPLINK_NEW_KEY)
  bool estop_latched_ = false;
  std::uint32_t reported_drops_ = 0;
  std::uint32_t kernel_drops_base_ = 0;      // the socket's count at the last counter reset
  std::uint32_t reported_kernel_drops_ = 0;  // as of the last CMD_KERNEL_DROPS event
  bool initialised_ = false;
};

}  // namespace petra::fsw
