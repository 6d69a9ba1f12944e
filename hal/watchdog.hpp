// Watchdog: the executive kicks it once per loop cycle; a hung loop stops
// the kicks and the device resets the computer. LinuxWatchdog drives a
// /dev/watchdog-style device ("k" kicks it; "V" before close disarms it).
// Without a configured device there is no watchdog (development hosts).
#pragma once

#include "algo/core/result.hpp"

namespace petra::hal {

class Watchdog {
 public:
  virtual ~Watchdog() = default;
  virtual void kick() = 0;
};

class LinuxWatchdog final : public Watchdog {
 public:
  LinuxWatchdog() = default;
  ~LinuxWatchdog() override;
  LinuxWatchdog(const LinuxWatchdog&) = delete;
  LinuxWatchdog& operator=(const LinuxWatchdog&) = delete;

  Status open(const char* device);
  void kick() override;
  // Disarms (magic close) and closes: for a deliberate stop only.
  void disarm();
  unsigned kicks() const { return kicks_; }

 private:
  int fd_ = -1;
  unsigned kicks_ = 0;
};

}  // namespace petra::hal
