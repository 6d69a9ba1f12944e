// The executive's statistics, reported in housekeeping (RESET_COUNTERS
// clears them, keeping the replay guard's last counter and the totals of
// cycles, frames and evaluations).
#pragma once

#include <cstdint>

#include "algo/wire/reasons.hpp"

namespace petra::fsw {

struct CommandCounters {
  std::uint32_t received = 0;
  std::uint32_t accepted = 0;
  std::uint32_t rejected = 0;
  std::uint32_t completed = 0;
  std::uint32_t failed = 0;
  std::uint32_t last_counter = 0;
  std::uint32_t unreported = 0;    // throttled rejections (RejectionThrottle)
  std::uint32_t kernel_drops = 0;  // datagrams the kernel dropped on the command port
  std::uint8_t last_function_code = 0;
  Reason last_reason = Reason::NONE;
};

struct LoopCounters {
  std::uint32_t cycles = 0;
  std::uint32_t overruns = 0;
  std::uint32_t max_cycle_us = 0;
  std::uint32_t tlm_sent = 0;
  std::uint32_t tlm_send_errors = 0;
  std::uint32_t faults = 0;
  std::uint32_t frames = 0;
  std::uint32_t evaluations = 0;
};

}  // namespace petra::fsw
