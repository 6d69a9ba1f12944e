// The simulated arm's drives on one CAN port: routes every received frame to
// each drive (each picks what is addressed to it) and steps them. One port is
// enough: the drives never talk to each other, only to the master.
// Works on the loopback bus (tests, `petra sim-arm --loopback`) and on
// SocketCAN (`petra sim-arm --can vcan0`, the HIL bench).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "algo/core/result.hpp"
#include "hal/can.hpp"
#include "sim/arm/sim_drive.hpp"

namespace petra::sim {

class SimArmBus final : private FrameSink {
 public:
  static constexpr std::size_t kMaxDrives = 8;
  static constexpr std::size_t kMaxFramesPerStep = 256;

  Status configure(std::span<const SimDriveParams> drives, hal::CanPort& port);
  void power_on(std::int64_t now_ms);
  // Receives what is pending, then advances every drive to now_ms.
  void step(std::int64_t now_ms);

  std::size_t size() const { return count_; }
  SimDrive& drive(std::size_t i) { return drives_[i]; }
  const SimDrive& drive(std::size_t i) const { return drives_[i]; }
  // Fault injection that needs to send (EMCY): through the bus port.
  void inject_fault(std::size_t i, std::uint16_t emcy_code) {
    drives_[i].inject_fault(emcy_code, *this);
  }
  std::uint32_t send_errors() const { return send_errors_; }

 private:
  void send(const hal::CanFrame& frame) override;

  hal::CanPort* port_ = nullptr;
  std::array<SimDrive, kMaxDrives> drives_{};
  std::size_t count_ = 0;
  std::uint32_t send_errors_ = 0;
};

}  // namespace petra::sim
