#include "hal/can_loopback.hpp"

#include "hal/socketcan.hpp"

#include <chrono>

namespace petra::hal {

Result<CanLoopbackBus::Endpoint*> CanLoopbackBus::attach(std::span<const CanFilter> filters) {
  if (filters.size() > kMaxCanFilters) {
    return Error::make(Errc::capacity_exceeded, "can loopback: %zu filters, at most %zu",
                       filters.size(), kMaxCanFilters);
  }
  const std::lock_guard lock(mutex_);
  if (count_ == kMaxEndpoints) {
    return Error::make(Errc::capacity_exceeded, "can loopback: all %zu endpoints attached",
                       kMaxEndpoints);
  }
  Endpoint& e = endpoints_[count_++];
  e.bus_ = this;
  for (std::size_t i = 0; i < filters.size(); ++i) e.filters_[i] = filters[i];
  e.filter_count_ = filters.size();
  return &e;
}

Status CanLoopbackBus::Endpoint::send(const CanFrame& frame) {
  PETRA_TRY(validate_frame(frame));
  CanLoopbackBus& bus = *bus_;
  {
    const std::lock_guard lock(bus.mutex_);
    if (health_.state == CanBusState::bus_off) {
      ++health_.tx_dropped;
      return Error::make(Errc::io_error, "can loopback: endpoint is bus-off");
    }
    ++health_.frames_sent;
    ++bus.carried_;
    for (std::size_t i = 0; i < bus.count_; ++i) {
      Endpoint& other = bus.endpoints_[i];
      if (&other == this || other.health_.state == CanBusState::bus_off) continue;
      bool accept = other.filter_count_ == 0;
      for (std::size_t f = 0; f < other.filter_count_ && !accept; ++f) {
        accept = filter_accepts(other.filters_[f], frame);
      }
      if (!accept) continue;
      if (!other.rx_.push(frame)) ++other.health_.rx_dropped;
    }
  }
  bus.arrived_.notify_all();
  return ok_status();
}

Result<bool> CanLoopbackBus::Endpoint::receive(CanFrame& out, int timeout_ms) {
  CanLoopbackBus& bus = *bus_;
  std::unique_lock lock(bus.mutex_);
  if (rx_.empty() && timeout_ms > 0) {
    bus.arrived_.wait_for(lock, std::chrono::milliseconds(timeout_ms),
                          [this] { return !rx_.empty(); });
  }
  if (!rx_.pop(out)) return false;
  ++health_.frames_received;
  return true;
}

CanHealth CanLoopbackBus::Endpoint::health() const {
  const std::lock_guard lock(bus_->mutex_);
  return health_;
}

void CanLoopbackBus::set_bus_off(Endpoint& endpoint, bool bus_off) {
  const std::lock_guard lock(mutex_);
  CanHealth& h = endpoint.health_;
  if (bus_off && h.state != CanBusState::bus_off) {
    h.state = CanBusState::bus_off;
    ++h.bus_off_count;
  } else if (!bus_off && h.state == CanBusState::bus_off) {
    h.state = CanBusState::error_active;
    ++h.restarts;
  }
}

void CanLoopbackBus::inject_error_frame(Endpoint& endpoint, std::uint32_t error_class,
                                        const std::array<std::uint8_t, 8>& data) {
  const std::lock_guard lock(mutex_);
  apply_error_frame(error_class, data, endpoint.health_);
}

std::uint32_t CanLoopbackBus::frames_carried() const {
  const std::lock_guard lock(mutex_);
  return carried_;
}

}  // namespace petra::hal
