// RejectionThrottle: keeps rejections that anyone can cause without the key
// (datagrams refused before their HMAC verified, and replays of recorded
// commands) from flooding the downlink, as F Prime's event throttles do. Per
// reason, the first rejection of each one-second window is reported in full
// (its event and its REJECTED ack); the rest are only counted, and when the
// window ends one CMD_REJECTS_UNREPORTED event per reason gives their number.
// Authenticated rejections (a fresh counter, so only a key holder) are never
// throttled.
#pragma once

#include <array>
#include <cstdint>

#include "algo/wire/reasons.hpp"

namespace petra::fsw {

class RejectionThrottle {
 public:
  static constexpr std::int64_t kWindowNs = 1000000000;  // one report per reason per second
  static constexpr std::uint32_t kWindowMs = 1000;

  // Reasons this throttle applies to: those decided before the counter is used up.
  static constexpr bool applies(Reason r) {
    return r != Reason::NONE && static_cast<unsigned>(r) <= static_cast<unsigned>(Reason::REPLAY);
  }

  // True when this rejection is to be reported in full; false: counted only.
  bool admit(Reason r);

  // Called every cycle. Once the window has ended: calls report(reason, unreported) for every
  // reason with unreported rejections in it, then opens a new window.
  // Returns true when a window ended.
  template <class Report>
  bool end_window(std::int64_t now_ns, Report&& report) {
    if (now_ns - window_start_ns_ < kWindowNs) return false;
    for (std::size_t i = 0; i < kSlots; ++i)
      if (unreported_[i] != 0) report(static_cast<Reason>(i), unreported_[i]);
    unreported_ = {};
    reported_ = {};
    window_start_ns_ = now_ns;
    return true;
  }

 private:
  static constexpr std::size_t kSlots = static_cast<std::size_t>(Reason::REPLAY) + 1;
  std::array<bool, kSlots> reported_{};
  std::array<std::uint32_t, kSlots> unreported_{};
  std::int64_t window_start_ns_ = 0;
};

}  // namespace petra::fsw
