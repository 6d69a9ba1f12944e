// CANopen master for the arm's drives (one CiA 402 drive per joint) on one
// CanPort. Each control cycle, step(now):
//   1. drains at most kMaxFramesPerStep received frames and routes them by
//      COB-ID to the drive links (frames from other nodes are counted, not used);
//   2. steps every drive link (timeouts, SDO configuration, CiA 402, RPDO);
//   3. sends its own heartbeat every master_heartbeat_ms and one SYNC, which
//      makes every operational drive answer with TPDO1 (statusword, position).
// Safety policy, independent of the executive: when any drive faults, every
// other enabled drive gets a quick stop in the same cycle.
// Events (boot, enable, faults, emergencies, bad frames, bus state) wait in a
// fixed queue for the executive (pop_event); overflow is counted.
// Protocol logic only: no OS calls; time is the caller's monotonic ms.
// Memory: fixed-size (kMaxDrives links, kEventCapacity events); no heap.
#pragma once

#include <array>
#include <cstdint>
#include <span>

#include "algo/core/result.hpp"
#include "hal/can.hpp"
#include "hal/canopen/drive_link.hpp"

namespace petra::canopen {

struct MasterEvent {
  std::uint8_t node = 0;  // 0: the bus itself
  LinkEvent event = LinkEvent::booted;
  std::uint32_t detail = 0;
};

struct MasterCounters {
  std::uint32_t frames_sent = 0;
  std::uint32_t frames_received = 0;
  std::uint32_t send_errors = 0;     // the port refused a frame (queue full, bus-off)
  std::uint32_t foreign_frames = 0;  // well-formed, not for us (other nodes, other masters)
  std::uint32_t bad_frames = 0;      // from our drives, failed validation
  std::uint32_t events_dropped = 0;  // event queue full
  std::uint32_t receive_errors = 0;  // the port failed to receive
};

class CanopenMaster final : private LinkOutput {
 public:
  static constexpr std::size_t kMaxDrives = 8;
  static constexpr std::size_t kMaxFramesPerStep = 64;
  static constexpr std::size_t kEventCapacity = 64;

  // Init: checks every drive config, distinct node ids, and the timing.
  Status configure(std::span<const DriveConfig> drives, const LinkTiming& timing,
                   hal::CanPort& port);

  // Commands for all drives (take effect over the next steps).
  void boot(std::int64_t now_ms);  // NMT reset, SDO configuration, NMT start
  void enable(std::int64_t now_ms);
  void quick_stop();
  void disable();
  // Targets in radians, one per drive, each inside its drive's range.
  Status set_targets(std::span<const double> positions_rad);

  void step(std::int64_t now_ms);

  std::size_t drive_count() const { return count_; }
  const DriveLink& drive(std::size_t i) const { return links_[i]; }
  bool all_in(LinkState state) const;
  bool any_fault() const;
  bool all_targets_reached() const;
  hal::CanBusState bus_state() const { return bus_state_; }
  const MasterCounters& counters() const { return counters_; }
  bool pop_event(MasterEvent& out);

 private:
  void send(const CanFrame& frame) override;
  void event(std::uint8_t node, LinkEvent event, std::uint32_t detail) override;
  void route(const CanFrame& frame, std::int64_t now_ms);

  hal::CanPort* port_ = nullptr;
  LinkTiming timing_;
  std::array<DriveLink, kMaxDrives> links_{};
  std::size_t count_ = 0;
  std::array<std::int8_t, 128> index_of_node_{};  // -1: not ours
  std::array<MasterEvent, kEventCapacity> events_{};
  std::size_t event_head_ = 0;
  std::size_t event_size_ = 0;
  MasterCounters counters_;
  hal::CanBusState bus_state_ = hal::CanBusState::error_active;
  std::int64_t last_heartbeat_ms_ = 0;
  bool heartbeat_started_ = false;
  std::array<bool, kMaxDrives> was_fault_{};
};

}  // namespace petra::canopen
