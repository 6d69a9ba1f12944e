#include "fsw/mode_manager.hpp"

namespace petra::fsw {

bool ModeManager::allowed(Mode from, Mode to) {
  if (from == to) return false;
  if (to == Mode::SAFE) return true;  // any fault or the ground, from anywhere
  switch (from) {
    case Mode::IDLE:
      return to == Mode::ACQUIRE || to == Mode::EVALUATE || to == Mode::ARM_MOVING;
    case Mode::BOOT:  // every other mode leads back to IDLE only
    case Mode::ACQUIRE:
    case Mode::EVALUATE:
    case Mode::ARM_MOVING:
    case Mode::SAFE:
      return to == Mode::IDLE;
  }
  return false;
}

bool ModeManager::request(Mode to, std::uint8_t cause) {
  if (!allowed(mode_, to)) return false;
  const Mode from = mode_;
  mode_ = to;
  events_->raise(EventId::MODE_CHANGED, static_cast<std::int32_t>(from),
                 static_cast<std::int32_t>(to), cause);
  return true;
}

}  // namespace petra::fsw
