// FlightArm: the executive's ArmPort on top of the ArmService (fsw/arm/
// arm_service.hpp): takes time from the executive's clock, turns the service's
// events into the executive's events (a drive fault, a lost heartbeat and a
// bus-off ask for SAFE) and fills ARM_STATUS telemetry.
// Memory: the service and the master inside; no heap after configure().
#pragma once

#include "fsw/arm/arm_service.hpp"
#include "fsw/arm_port.hpp"
#include "hal/clock.hpp"

namespace petra::fsw::arm {

class FlightArm final : public fsw::ArmPort {
 public:
  // Configures the service on `port` and boots the drives.
  Status init(const ArmServiceConfig& config, hal::CanPort& port, const hal::Clock& clock);

  Status start_goto(const ArmTarget& target) override;
  Status start_stow() override;
  ArmProgress poll() override;
  void quick_stop() override;
  bool pop_event(ArmEventOut& out) override;
  bool status(tlm::ArmStatus& out) const override;

  // Reboots the drives after a fault (the operator leaves SAFE); no-op otherwise.
  Status reset() override;
  const ArmService& service() const { return service_; }

 private:
  std::int64_t now_ms() const { return clock_->monotonic_ns() / 1000000; }

  ArmService service_;
  const hal::Clock* clock_ = nullptr;
};

}  // namespace petra::fsw::arm
