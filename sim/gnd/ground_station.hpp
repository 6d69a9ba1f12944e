// The ground station's link side: signs and sends telecommands on the uplink
// (key file + counter file, as `petra cmd`), receives and decodes the
// downlink on a thread, reassembles products and publishes every decoded
// packet to the pages through the EventHub:
//   event "tlm":     {"tlm": <petra tlm --json object>, "line": "<text>", "names": {...}}
//                    ARM_STATUS also carries "skeleton": the arm drawn from its
//                    measured joints (arm_model.hpp)
//   event "sent":    {"command": "SELECT_ROI", "counter": 7, "code": 16}
//   event "product": {"kind": "disparity", "id": 3, "width": .., "height": .., "format": ..}
// PRODUCT chunks themselves are not forwarded (a product is thousands).
#pragma once

#include <atomic>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "algo/core/result.hpp"
#include "cmd/auth.hpp"
#include "cmd/commands.hpp"
#include "hal/udp_link.hpp"
#include "sim/gnd/arm_model.hpp"
#include "sim/gnd/event_hub.hpp"
#include "sim/ground/product_assembler.hpp"
#include "sim/ground/seq_tracker.hpp"
#include "sim/ground/tlm_archive.hpp"

namespace petra::gnd {

struct StationOptions {
  std::string fsw_host = "127.0.0.1";  // petra-fsw command address
  int cmd_port = 47100;
  std::string tlm_host = "127.0.0.1";  // where telemetry arrives (local address)
  int tlm_port = 47101;
  std::string key_path = "petra.key";
  std::string counter_path;  // empty: KEY.counter (shared with `petra cmd`)
  std::string left_image;    // optional: shown until a LEFT_IMAGE product arrives
  arm::ArmGeometry arm_geometry = arm::rover_arm_geometry();  // as petra-fsw's arm.mount
  std::string archive_path;  // optional: every packet received kept there (tlm_archive.hpp)
};

// Names the page shows beside the numbers of a packet (the "names" of a "tlm" message).
std::string packet_names_json(const tlm::TmPacket& p);

class GroundStation {
 public:
  GroundStation() = default;
  ~GroundStation() { stop(); }
  GroundStation(const GroundStation&) = delete;
  GroundStation& operator=(const GroundStation&) = delete;

  // Loads the key (and the optional image), opens both links, starts the
  // telemetry thread.
  Status start(const StationOptions& options);
  void stop();

  // Signs `c` with the next counter and sends it; returns the counter.
  Result<std::uint32_t> send(cmd::Command c);

  // Latest complete product of a kind (1 LEFT_IMAGE .. 5 PROPOSALS).
  std::optional<ground::Product> product(std::uint8_t kind) const;

  // The last PROPOSALS packet received (what a pick refers to); nullopt before one.
  std::optional<tlm::Proposals> last_proposals() const;

  EventHub& hub() { return hub_; }
  const std::string& archive_path() const { return options_.archive_path; }
  const ArmModel& arm_model() const { return arm_model_; }
  // Measured joints of the latest ARM_STATUS (the stowed pose before one).
  std::array<double, arm::kJointCount> arm_joints_deg() const;
  std::uint64_t packets() const { return packets_.load(); }
  std::uint64_t bad_packets() const { return bad_packets_.load(); }
  // Packets the archive could not store (its error is published as "archive_error").
  std::uint64_t archive_errors() const { return archive_errors_.load(); }

 private:
  void receive_loop();
  void publish_packet(const tlm::TmPacket& p);
  void keep_product(ground::Product p);
  void archive(std::span<const std::uint8_t> raw, const tlm::TmPacket* p);

  StationOptions options_;
  cmd::AuthKey key_{};
  hal::UdpLink uplink_;
  hal::UdpLink downlink_;
  std::mutex send_mutex_;
  EventHub hub_;
  ground::ProductAssembler assembler_;
  ground::SeqTracker seqs_;  // receive thread only
  mutable std::mutex products_mutex_;
  std::map<std::uint8_t, ground::Product> products_;
  ArmModel arm_model_;
  mutable std::mutex arm_mutex_;
  std::array<double, arm::kJointCount> arm_joints_deg_{0, 0, 145, 35, 0};
  mutable std::mutex proposals_mutex_;
  std::optional<tlm::Proposals> proposals_;
  std::thread thread_;
  std::atomic<bool> running_{false};
  std::atomic<std::uint64_t> packets_{0};
  std::atomic<std::uint64_t> bad_packets_{0};
  std::atomic<std::uint64_t> archive_errors_{0};
  std::unique_ptr<ground::TlmArchive> archive_;  // used by the telemetry thread only
};

}  // namespace petra::gnd
