#include "hal/canopen/canopen_master.hpp"

namespace petra::canopen {

Status CanopenMaster::configure(std::span<const DriveConfig> drives, const LinkTiming& timing,
                                hal::CanPort& port) {
  if (drives.empty() || drives.size() > kMaxDrives) {
    return Error::make(Errc::out_of_range, "canopen master: %zu drives, expected 1..%zu",
                       drives.size(), kMaxDrives);
  }
  if (timing.master_heartbeat_ms == 0 || timing.sdo_timeout_ms == 0) {
    return Error::make(Errc::non_positive,
                       "canopen master: heartbeat and SDO times must be > 0 ms");
  }
  index_of_node_.fill(-1);
  for (std::size_t i = 0; i < drives.size(); ++i) {
    PETRA_TRY(links_[i].configure(drives[i], timing));
    const std::uint8_t node = drives[i].node_id;
    if (index_of_node_[node] >= 0)
      return Error::make(Errc::invalid_argument, "canopen master: node %u twice", node);
    index_of_node_[node] = static_cast<std::int8_t>(i);
  }
  if (index_of_node_[timing.master_node_id] >= 0) {
    return Error::make(Errc::invalid_argument, "canopen master: master node id %u used by a drive",
                       timing.master_node_id);
  }
  port_ = &port;
  timing_ = timing;
  count_ = drives.size();
  event_head_ = event_size_ = 0;
  counters_ = MasterCounters{};
  was_fault_.fill(false);
  heartbeat_started_ = false;
  return ok_status();
}

void CanopenMaster::boot(std::int64_t now_ms) {
  for (std::size_t i = 0; i < count_; ++i) {
    links_[i].reboot(now_ms, *this);
    was_fault_[i] = false;
  }
}

void CanopenMaster::enable(std::int64_t now_ms) {
  for (std::size_t i = 0; i < count_; ++i) links_[i].enable(now_ms);
}

void CanopenMaster::quick_stop() {
  for (std::size_t i = 0; i < count_; ++i) links_[i].quick_stop(*this);
}

void CanopenMaster::disable() {
  for (std::size_t i = 0; i < count_; ++i) links_[i].disable(*this);
}

Status CanopenMaster::set_targets(std::span<const double> rad) {
  if (rad.size() != count_) {
    return Error::make(Errc::invalid_argument, "canopen master: %zu targets for %zu drives",
                       rad.size(), count_);
  }
  // All or nothing: check every drive before changing any.
  for (std::size_t i = 0; i < count_; ++i) {
    if (links_[i].state() != LinkState::ready) {
      return Error::make(Errc::not_ready, "drive %u is %s, not ready", links_[i].node_id(),
                         link_state_name(links_[i].state()));
    }
  }
  DriveLink copy;
  for (std::size_t i = 0; i < count_; ++i) {
    copy = links_[i];
    PETRA_TRY(copy.set_target(rad[i]));
  }
  for (std::size_t i = 0; i < count_; ++i) (void)links_[i].set_target(rad[i]);
  return ok_status();
}

bool CanopenMaster::all_in(LinkState state) const {
  for (std::size_t i = 0; i < count_; ++i) {
    if (links_[i].state() != state) return false;
  }
  return count_ > 0;
}

bool CanopenMaster::any_fault() const {
  for (std::size_t i = 0; i < count_; ++i) {
    if (links_[i].state() == LinkState::fault) return true;
  }
  return false;
}

bool CanopenMaster::all_targets_reached() const {
  for (std::size_t i = 0; i < count_; ++i) {
    if (!links_[i].target_reached()) return false;
  }
  return count_ > 0;
}

bool CanopenMaster::pop_event(MasterEvent& out) {
  if (event_size_ == 0) return false;
  out = events_[event_head_];
  event_head_ = (event_head_ + 1) % kEventCapacity;
  --event_size_;
  return true;
}

void CanopenMaster::send(const CanFrame& frame) {
  if (port_->send(frame).ok()) {
    ++counters_.frames_sent;
  } else {
    ++counters_.send_errors;
  }
}

void CanopenMaster::event(std::uint8_t node, LinkEvent e, std::uint32_t detail) {
  if (e == LinkEvent::bad_frame) ++counters_.bad_frames;
  if (event_size_ == kEventCapacity) {
    ++counters_.events_dropped;
    return;
  }
  events_[(event_head_ + event_size_) % kEventCapacity] = MasterEvent{node, e, detail};
  ++event_size_;
}

void CanopenMaster::route(const CanFrame& frame, std::int64_t now_ms) {
  const CobId c = split_cob_id(frame.id);
  const int index = (!frame.extended && c.known && c.node <= 127) ? index_of_node_[c.node] : -1;
  if (index < 0 || frame.rtr) {
    ++counters_.foreign_frames;
    return;
  }
  DriveLink& link = links_[static_cast<std::size_t>(index)];
  switch (c.function) {
    case Function::heartbeat:
      link.on_heartbeat(frame, now_ms, *this);
      return;
    case Function::sdo_tx:
      link.on_sdo(frame, now_ms, *this);
      return;
    case Function::tpdo1:
      link.on_tpdo(frame, now_ms, *this);
      return;
    case Function::emcy:
      link.on_emcy(frame, *this);
      return;
    default:
      // RPDO or SDO requests to our drives from someone else: not ours to act on.
      ++counters_.foreign_frames;
      return;
  }
}

void CanopenMaster::step(std::int64_t now_ms) {
  if (port_ == nullptr) return;
  hal::CanFrame frame;
  for (std::size_t n = 0; n < kMaxFramesPerStep; ++n) {
    auto got = port_->receive(frame, 0);
    if (!got.ok()) {
      ++counters_.receive_errors;
      break;
    }
    if (!*got) break;
    ++counters_.frames_received;
    route(frame, now_ms);
  }
  const hal::CanBusState bus = port_->health().state;
  if (bus != bus_state_) {
    bus_state_ = bus;
    event(0, LinkEvent::bus_state, static_cast<std::uint32_t>(bus));
  }
  bool live = false;
  for (std::size_t i = 0; i < count_; ++i) {
    links_[i].step(now_ms, *this);
    const LinkState s = links_[i].state();
    live = live || s == LinkState::operational || s == LinkState::enabling ||
           s == LinkState::ready || s == LinkState::quick_stopped || s == LinkState::starting;
  }
  // One drive down stops the others (an arm with a limp joint must not move on).
  for (std::size_t i = 0; i < count_; ++i) {
    const bool faulted = links_[i].state() == LinkState::fault;
    if (faulted && !was_fault_[i]) quick_stop();
    was_fault_[i] = faulted;
  }
  if (!heartbeat_started_ || now_ms - last_heartbeat_ms_ >= timing_.master_heartbeat_ms) {
    send(make_heartbeat(timing_.master_node_id, NmtState::operational));
    last_heartbeat_ms_ = now_ms;
    heartbeat_started_ = true;
  }
  if (live) send(make_sync());
}

}  // namespace petra::canopen
