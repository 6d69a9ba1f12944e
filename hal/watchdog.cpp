#include "hal/watchdog.hpp"

#include <fcntl.h>
#include <unistd.h>

namespace petra::hal {

LinuxWatchdog::~LinuxWatchdog() {
  if (fd_ >= 0) ::close(fd_);  // no magic close: an unexpected exit still resets
}

Status LinuxWatchdog::open(const char* device) {
  fd_ = ::open(device, O_WRONLY | O_CLOEXEC);
  if (fd_ < 0) return Error::make(Errc::io_error, "watchdog %s: cannot open", device);
  return {};
}

void LinuxWatchdog::kick() {
  if (fd_ >= 0 && ::write(fd_, "k", 1) == 1) ++kicks_;
}

void LinuxWatchdog::disarm() {
  if (fd_ < 0) return;
  (void)::write(fd_, "V", 1);
  ::close(fd_);
  fd_ = -1;
}

}  // namespace petra::hal
