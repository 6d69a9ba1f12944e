// ModeManager: the only owner of the mode. Changes follow the transition
// table in docs/executive.md; each change raises MODE_CHANGED.
#pragma once

#include <cstdint>

#include "cmd/mode.hpp"
#include "fsw/event_log.hpp"

namespace petra::fsw {

class ModeManager {
 public:
  void init(EventLog* events) { events_ = events; }
  Mode mode() const { return mode_; }
  static bool allowed(Mode from, Mode to);
  // Changes the mode when allowed; false (and no change) otherwise.
  // cause: function code of the command behind it, 0 for the executive itself.
  bool request(Mode to, std::uint8_t cause);

 private:
  EventLog* events_ = nullptr;
  Mode mode_ = Mode::BOOT;
};

}  // namespace petra::fsw
