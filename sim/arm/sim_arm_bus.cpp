#include "sim/arm/sim_arm_bus.hpp"

namespace petra::sim {

Status SimArmBus::configure(std::span<const SimDriveParams> drives, hal::CanPort& port) {
  if (drives.empty() || drives.size() > kMaxDrives) {
    return Error::make(Errc::out_of_range, "sim arm: %zu drives, expected 1..%zu", drives.size(),
                       kMaxDrives);
  }
  for (std::size_t i = 0; i < drives.size(); ++i) {
    if (!canopen::valid_node_id(drives[i].node_id)) {
      return Error::make(Errc::out_of_range, "sim arm: node id %u outside 1..127",
                         drives[i].node_id);
    }
    for (std::size_t j = 0; j < i; ++j) {
      if (drives[j].node_id == drives[i].node_id) {
        return Error::make(Errc::invalid_argument, "sim arm: node id %u twice", drives[i].node_id);
      }
    }
  }
  for (std::size_t i = 0; i < drives.size(); ++i) drives_[i] = SimDrive(drives[i]);
  count_ = drives.size();
  port_ = &port;
  return ok_status();
}

void SimArmBus::power_on(std::int64_t now_ms) {
  for (std::size_t i = 0; i < count_; ++i) drives_[i].power_on(now_ms);
}

void SimArmBus::step(std::int64_t now_ms) {
  if (port_ == nullptr) return;
  hal::CanFrame frame;
  for (std::size_t n = 0; n < kMaxFramesPerStep; ++n) {
    auto got = port_->receive(frame, 0);
    if (!got.ok() || !*got) break;
    for (std::size_t i = 0; i < count_; ++i) drives_[i].on_frame(frame, now_ms, *this);
  }
  for (std::size_t i = 0; i < count_; ++i) drives_[i].step(now_ms, *this);
}

void SimArmBus::send(const hal::CanFrame& frame) {
  if (!port_->send(frame).ok()) ++send_errors_;
}

}  // namespace petra::sim
