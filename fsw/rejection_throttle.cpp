#include "fsw/rejection_throttle.hpp"

namespace petra::fsw {

bool RejectionThrottle::admit(Reason r) {
  if (!applies(r)) return true;
  const auto i = static_cast<std::size_t>(r);
  if (!reported_[i]) {
    reported_[i] = true;
    return true;
  }
  ++unreported_[i];
  return false;
}

}  // namespace petra::fsw
