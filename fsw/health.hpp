// Health: component heartbeats with a deadline. Each rate group and the
// pipeline worker beat; check() reports a component silent longer than the
// timeout once (until it beats again), and the executive enters SAFE.
#pragma once

#include <array>
#include <atomic>
#include <cstdint>

namespace petra::fsw {

// Component ids (the {n:component} argument of HEARTBEAT_LOST).
enum class Component : std::uint8_t {
  UPLINK = 0,
  PIPELINE = 1,
  PRODUCTS = 2,
  HOUSEKEEPING = 3,
  DOWNLINK = 4,
  WORKER = 5,
  ARM = 6
};
inline constexpr std::size_t kComponentCount = 7;
const char* component_name(Component c);

class Health {
 public:
  // Thread-safe: the worker beats from its own thread.
  void beat(Component c, std::int64_t now_ns);
  // Exempts a component (e.g. the worker while it runs a job: EVAL_TIMEOUT_S covers it).
  void set_exempt(Component c, bool exempt, std::int64_t now_ns);
  // The first component silent for longer than its timeout, newly so; -1 when all are fine.
  int check(std::int64_t now_ns, const std::array<std::int64_t, kComponentCount>& timeout_ns,
            std::int64_t& silent_ns);
  void reset(std::int64_t now_ns);

 private:
  std::array<std::atomic<std::int64_t>, kComponentCount> last_{};
  std::array<std::atomic<bool>, kComponentCount> exempt_{};
  std::array<bool, kComponentCount> reported_{};
};

}  // namespace petra::fsw
