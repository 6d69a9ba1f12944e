#include "hal/socketcan.hpp"

#include <fcntl.h>
#include <linux/can.h>
#include <linux/can/error.h>
#include <linux/can/raw.h>
#include <net/if.h>
#include <poll.h>
#include <sys/ioctl.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "hal/errno_text.hpp"

namespace petra::hal {

namespace {

// Bounded work per receive(): error frames and stale frames are skipped, but
// never more than this many per call.
constexpr int kMaxReadsPerReceive = 32;

can_frame to_kernel(const CanFrame& f) {
  can_frame k{};
  k.can_id = f.id;
  if (f.extended) k.can_id |= CAN_EFF_FLAG;
  if (f.rtr) k.can_id |= CAN_RTR_FLAG;
  k.len = f.len;
  std::memcpy(k.data, f.data.data(), f.len);
  return k;
}

CanFrame from_kernel(const can_frame& k) {
  CanFrame f;
  f.extended = (k.can_id & CAN_EFF_FLAG) != 0;
  f.rtr = (k.can_id & CAN_RTR_FLAG) != 0;
  f.id = k.can_id & (f.extended ? CAN_EFF_MASK : CAN_SFF_MASK);
  f.len = k.len > 8 ? 8 : k.len;
  std::memcpy(f.data.data(), k.data, f.len);
  return f;
}

}  // namespace

bool socketcan_available() {
  const int fd = ::socket(PF_CAN, SOCK_RAW, CAN_RAW);
  if (fd < 0) return false;
  ::close(fd);
  return true;
}

void apply_error_frame(std::uint32_t can_id, std::span<const std::uint8_t, 8> data, CanHealth& h) {
  const std::uint32_t cls = can_id & CAN_ERR_MASK;
  ++h.error_frames;
  h.last_error_class = cls;
  if (cls & CAN_ERR_BUSOFF) {
    if (h.state != CanBusState::bus_off) ++h.bus_off_count;
    h.state = CanBusState::bus_off;
    return;
  }
  if (cls & CAN_ERR_RESTARTED) {
    if (h.state == CanBusState::bus_off) ++h.restarts;
    h.state = CanBusState::error_active;
  }
  if (cls & CAN_ERR_CRTL) {
    const std::uint8_t c = data[1];
    if (c & CAN_ERR_CRTL_ACTIVE) h.state = CanBusState::error_active;
    if (c & (CAN_ERR_CRTL_RX_WARNING | CAN_ERR_CRTL_TX_WARNING))
      h.state = CanBusState::error_warning;
    if (c & (CAN_ERR_CRTL_RX_PASSIVE | CAN_ERR_CRTL_TX_PASSIVE))
      h.state = CanBusState::error_passive;
    if (c & CAN_ERR_CRTL_RX_OVERFLOW) ++h.rx_dropped;
  }
}

SocketCanPort::~SocketCanPort() {
  close();
}

void SocketCanPort::close() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  tx_.clear();
}

Status SocketCanPort::open(const char* interface, std::span<const CanFilter> filters) {
  close();
  if (interface == nullptr || std::strlen(interface) == 0 || std::strlen(interface) >= IFNAMSIZ) {
    return Error::make(Errc::invalid_argument, "socketcan: interface name empty or longer than %d",
                       IFNAMSIZ - 1);
  }
  if (filters.size() > kMaxCanFilters) {
    return Error::make(Errc::capacity_exceeded, "socketcan: %zu filters, at most %zu",
                       filters.size(), kMaxCanFilters);
  }
  const int fd = ::socket(PF_CAN, SOCK_RAW | SOCK_NONBLOCK | SOCK_CLOEXEC, CAN_RAW);
  if (fd < 0)
    return Error::make(Errc::io_error, "socketcan: socket(AF_CAN): %s", errno_text(errno));
  auto fail = [fd](const char* what) {
    const int err = errno;
    ::close(fd);
    return Error::make(Errc::io_error, "socketcan: %s: %s", what, errno_text(err));
  };
  ifreq ifr{};
  std::strncpy(ifr.ifr_name, interface, IFNAMSIZ - 1);
  if (::ioctl(fd, SIOCGIFINDEX, &ifr) < 0) return fail(interface);
  can_filter kf[kMaxCanFilters]{};
  for (std::size_t i = 0; i < filters.size(); ++i) {
    kf[i].can_id = filters[i].id;
    kf[i].can_mask = filters[i].mask;
  }
  if (!filters.empty() &&
      ::setsockopt(fd, SOL_CAN_RAW, CAN_RAW_FILTER, kf,
                   static_cast<socklen_t>(sizeof(can_filter) * filters.size())) < 0) {
    return fail("CAN_RAW_FILTER");
  }
  const can_err_mask_t err_mask = CAN_ERR_MASK;
  if (::setsockopt(fd, SOL_CAN_RAW, CAN_RAW_ERR_FILTER, &err_mask, sizeof err_mask) < 0) {
    return fail("CAN_RAW_ERR_FILTER");
  }
  const int on = 1;
  if (::setsockopt(fd, SOL_SOCKET, SO_RXQ_OVFL, &on, sizeof on) < 0) return fail("SO_RXQ_OVFL");
  sockaddr_can addr{};
  addr.can_family = AF_CAN;
  addr.can_ifindex = ifr.ifr_ifindex;
  if (::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) < 0) return fail("bind");
  fd_ = fd;
  health_ = CanHealth{};
  kernel_drops_ = 0;
  return ok_status();
}

Status SocketCanPort::write_now(const CanFrame& frame, bool& would_block) {
  would_block = false;
  const can_frame k = to_kernel(frame);
  const ssize_t n = ::write(fd_, &k, sizeof k);
  if (n == static_cast<ssize_t>(sizeof k)) {
    ++health_.frames_sent;
    return ok_status();
  }
  if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK || errno == ENOBUFS)) {
    would_block = true;
    return ok_status();
  }
  if (n < 0 && errno == ENETDOWN) {
    health_.state = CanBusState::bus_off;
    return Error::make(Errc::io_error, "socketcan: interface down");
  }
  return Error::make(Errc::io_error, "socketcan: write: %s",
                     n < 0 ? errno_text(errno) : "short write");
}

Status SocketCanPort::flush_queue() {
  while (!tx_.empty()) {
    bool would_block = false;
    PETRA_TRY(write_now(tx_.front(), would_block));
    if (would_block) break;
    CanFrame sent;
    (void)tx_.pop(sent);
  }
  health_.tx_queued = static_cast<std::uint32_t>(tx_.size());
  return ok_status();
}

Status SocketCanPort::send(const CanFrame& frame) {
  if (fd_ < 0) return Error::make(Errc::not_ready, "socketcan: port not open");
  PETRA_TRY(validate_frame(frame));
  if (health_.state == CanBusState::bus_off) {
    ++health_.tx_dropped;
    return Error::make(Errc::io_error, "socketcan: controller is bus-off");
  }
  PETRA_TRY(flush_queue());
  if (tx_.empty()) {
    bool would_block = false;
    PETRA_TRY(write_now(frame, would_block));
    if (!would_block) return ok_status();
  }
  // Keep order: behind what is already queued.
  if (!tx_.push(frame)) {
    ++health_.tx_dropped;
    return Error::make(Errc::capacity_exceeded, "socketcan: send queue full (%zu frames)",
                       kTxQueueDepth);
  }
  health_.tx_queued = static_cast<std::uint32_t>(tx_.size());
  return ok_status();
}

Result<bool> SocketCanPort::receive(CanFrame& out, int timeout_ms) {
  if (fd_ < 0) return Error::make(Errc::not_ready, "socketcan: port not open");
  if (health_.state != CanBusState::bus_off) {
    // A failing flush is reported by the next send(); reception goes on.
    (void)flush_queue();
  }
  int wait_ms = timeout_ms < 0 ? 0 : timeout_ms;
  for (int i = 0; i < kMaxReadsPerReceive; ++i) {
    pollfd p{fd_, POLLIN, 0};
    const int ready = ::poll(&p, 1, wait_ms);
    if (ready < 0) {
      if (errno == EINTR) continue;
      return Error::make(Errc::io_error, "socketcan: poll: %s", errno_text(errno));
    }
    if (ready == 0) return false;
    if (p.revents & (POLLERR | POLLNVAL))
      return Error::make(Errc::io_error, "socketcan: socket error");
    can_frame k{};
    alignas(cmsghdr) char control[CMSG_SPACE(sizeof(std::uint32_t))];
    iovec iov{&k, sizeof k};
    msghdr msg{};
    msg.msg_iov = &iov;
    msg.msg_iovlen = 1;
    msg.msg_control = control;
    msg.msg_controllen = sizeof control;
    const ssize_t n = ::recvmsg(fd_, &msg, MSG_DONTWAIT);
    if (n < 0) {
      if (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR) continue;
      return Error::make(Errc::io_error, "socketcan: recvmsg: %s", errno_text(errno));
    }
    for (cmsghdr* c = CMSG_FIRSTHDR(&msg); c != nullptr; c = CMSG_NXTHDR(&msg, c)) {
      if (c->cmsg_level == SOL_SOCKET && c->cmsg_type == SO_RXQ_OVFL) {
        std::uint32_t drops = 0;
        std::memcpy(&drops, CMSG_DATA(c), sizeof drops);
        health_.rx_dropped += drops - kernel_drops_;
        kernel_drops_ = drops;
      }
    }
    if (n != static_cast<ssize_t>(sizeof k)) continue;  // not a classic CAN frame: ignore
    if (k.can_id & CAN_ERR_FLAG) {
      apply_error_frame(k.can_id, std::span<const std::uint8_t, 8>(k.data, 8), health_);
      wait_ms = 0;  // drain what is there, but do not wait again
      continue;
    }
    out = from_kernel(k);
    ++health_.frames_received;
    return true;
  }
  return false;
}

}  // namespace petra::hal
