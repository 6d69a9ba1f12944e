#include "hal/udp_link.hpp"

#include <arpa/inet.h>
#include <fcntl.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace petra::hal {

Result<in_addr> parse_ipv4(const char* host) {
  in_addr a{};
  if (std::strcmp(host, "localhost") == 0) host = "127.0.0.1";
  if (::inet_pton(AF_INET, host, &a) != 1)
    return Error::make(Errc::invalid_argument, "address '%s': not a numeric IPv4 address", host);
  return a;
}

UdpLink::~UdpLink() {
  close();
}

void UdpLink::close() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
}

Status UdpLink::open(const char* host, std::uint16_t port) {
  close();
  auto addr = parse_ipv4(host);
  if (!addr) return addr.error();
  fd_ = ::socket(AF_INET, SOCK_DGRAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  if (fd_ < 0) return Error::make(Errc::io_error, "udp: socket: %s", std::strerror(errno));
  kernel_drops_ = 0;
  const int on = 1;  // the kernel's drop count arrives with each datagram
  (void)::setsockopt(fd_, SOL_SOCKET, SO_RXQ_OVFL, &on, sizeof(on));
  sockaddr_in sa{};
  sa.sin_family = AF_INET;
  sa.sin_port = htons(port);
  sa.sin_addr = *addr;
  if (::bind(fd_, reinterpret_cast<const sockaddr*>(&sa), sizeof(sa)) != 0) {
    const int err = errno;
    close();
    return Error::make(Errc::io_error, "udp: bind %s:%u: %s", host, port, std::strerror(err));
  }
  return {};
}

Status UdpLink::set_peer(const char* host, std::uint16_t port) {
  auto addr = parse_ipv4(host);
  if (!addr) return addr.error();
  peer_ = {};
  peer_.sin_family = AF_INET;
  peer_.sin_port = htons(port);
  peer_.sin_addr = *addr;
  has_peer_ = true;
  return {};
}

void UdpLink::set_send_buffer(int bytes) {
  if (fd_ >= 0) ::setsockopt(fd_, SOL_SOCKET, SO_SNDBUF, &bytes, sizeof(bytes));
}

void UdpLink::set_receive_buffer(int bytes) {
  if (fd_ >= 0) ::setsockopt(fd_, SOL_SOCKET, SO_RCVBUF, &bytes, sizeof(bytes));
}

Result<Received> UdpLink::receive(std::span<std::uint8_t> buf) {
  if (fd_ < 0) return Error::make(Errc::not_ready, "udp: not open");
  iovec iov{buf.data(), buf.size()};
  alignas(cmsghdr) std::uint8_t control[CMSG_SPACE(sizeof(std::uint32_t))];
  msghdr msg{};
  msg.msg_iov = &iov;
  msg.msg_iovlen = 1;
  msg.msg_control = control;
  msg.msg_controllen = sizeof(control);
  const ssize_t n = ::recvmsg(fd_, &msg, MSG_DONTWAIT | MSG_TRUNC);
  if (n < 0) {
    if (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR) return Received{};
    return Error::make(Errc::io_error, "udp: recv: %s", std::strerror(errno));
  }
  for (cmsghdr* c = CMSG_FIRSTHDR(&msg); c != nullptr; c = CMSG_NXTHDR(&msg, c))
    if (c->cmsg_level == SOL_SOCKET && c->cmsg_type == SO_RXQ_OVFL)
      std::memcpy(&kernel_drops_, CMSG_DATA(c), sizeof(kernel_drops_));
  return Received{true, static_cast<std::size_t>(n)};
}

Result<Received> UdpLink::receive_wait(std::span<std::uint8_t> buf, int timeout_ms) {
  if (fd_ < 0) return Error::make(Errc::not_ready, "udp: not open");
  pollfd p{fd_, POLLIN, 0};
  const int r = ::poll(&p, 1, timeout_ms);
  if (r < 0 && errno != EINTR)
    return Error::make(Errc::io_error, "udp: poll: %s", std::strerror(errno));
  if (r <= 0) return Received{};
  return receive(buf);
}

SendResult UdpLink::send(std::span<const std::uint8_t> datagram) {
  if (fd_ < 0 || !has_peer_) return SendResult::error;
  const ssize_t n = ::sendto(fd_, datagram.data(), datagram.size(), MSG_DONTWAIT,
                             reinterpret_cast<const sockaddr*>(&peer_), sizeof(peer_));
  if (n == static_cast<ssize_t>(datagram.size())) return SendResult::sent;
  if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK || errno == ENOBUFS))
    return SendResult::would_block;
  return SendResult::error;
}

std::uint16_t UdpLink::local_port() const {
  sockaddr_in sa{};
  socklen_t len = sizeof(sa);
  if (fd_ < 0 || ::getsockname(fd_, reinterpret_cast<sockaddr*>(&sa), &len) != 0) return 0;
  return ntohs(sa.sin_port);
}

}  // namespace petra::hal
