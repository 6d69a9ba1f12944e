#include "fsw/health.hpp"

namespace petra::fsw {

const char* component_name(Component c) {
  switch (c) {
    case Component::UPLINK:
      return "UPLINK";
    case Component::PIPELINE:
      return "PIPELINE";
    case Component::PRODUCTS:
      return "PRODUCTS";
    case Component::HOUSEKEEPING:
      return "HOUSEKEEPING";
    case Component::DOWNLINK:
      return "DOWNLINK";
    case Component::WORKER:
      return "WORKER";
    case Component::ARM:
      return "ARM";
  }
  return "?";
}

void Health::beat(Component c, std::int64_t now_ns) {
  last_[static_cast<std::size_t>(c)].store(now_ns, std::memory_order_relaxed);
}

void Health::set_exempt(Component c, bool exempt, std::int64_t now_ns) {
  const auto i = static_cast<std::size_t>(c);
  last_[i].store(now_ns, std::memory_order_relaxed);
  exempt_[i].store(exempt, std::memory_order_relaxed);
}

void Health::reset(std::int64_t now_ns) {
  for (std::size_t i = 0; i < kComponentCount; ++i) {
    last_[i].store(now_ns, std::memory_order_relaxed);
    reported_[i] = false;
  }
}

int Health::check(std::int64_t now_ns, const std::array<std::int64_t, kComponentCount>& timeout_ns,
                  std::int64_t& silent_ns) {
  for (std::size_t i = 0; i < kComponentCount; ++i) {
    const std::int64_t silent = now_ns - last_[i].load(std::memory_order_relaxed);
    const bool late = !exempt_[i].load(std::memory_order_relaxed) && silent > timeout_ns[i];
    if (!late) {
      reported_[i] = false;
      continue;
    }
    if (reported_[i]) continue;
    reported_[i] = true;
    silent_ns = silent;
    return static_cast<int>(i);
  }
  return -1;
}

}  // namespace petra::fsw
