// The executive's modes: one list, shared by the command definitions (which
// modes allow a command), the mode manager (fsw/mode_manager) and the ICD.
// X(NAME, value, "meaning")
#pragma once

#include <cstdint>

#define PETRA_MODES(X)                                                           \
  X(BOOT, 0, "initialising: loading configuration, allocating, opening devices") \
  X(IDLE, 1, "ready: commands accepted, nothing running")                        \
  X(ACQUIRE, 2, "taking a stereo pair")                                          \
  X(EVALUATE, 3, "the pipeline is running on the selected ROI (worker thread)")  \
  X(ARM_MOVING, 4, "the arm is moving")                                          \
  X(SAFE, 5, "a fault or the ground stopped operations; only housekeeping commands")

namespace petra {

enum class Mode : std::uint8_t {
#define PETRA_MODE_ENUM(NAME, value, desc) NAME = (value),
  PETRA_MODES(PETRA_MODE_ENUM)
#undef PETRA_MODE_ENUM
};

inline constexpr int kModeCount = 6;

constexpr const char* mode_name(Mode m) {
  switch (m) {
#define PETRA_MODE_NAME(NAME, value, desc) \
  case Mode::NAME:                         \
    return #NAME;
    PETRA_MODES(PETRA_MODE_NAME)
#undef PETRA_MODE_NAME
  }
  return "?";
}

constexpr bool mode_valid(unsigned v) {
  return v < static_cast<unsigned>(kModeCount);
}

// Sets of modes as bit masks (bit n = Mode value n).
constexpr std::uint32_t mode_bit(Mode m) {
  return 1u << static_cast<unsigned>(m);
}
inline constexpr std::uint32_t kInIdle = 1u << 1;
inline constexpr std::uint32_t kInIdleOrSafe = (1u << 1) | (1u << 5);
// Every mode in which commands are serviced (all but BOOT).
inline constexpr std::uint32_t kInAnyMode = 0x3Eu;

// Mode changes the ground may ask for with SET_MODE: SAFE from anywhere, IDLE
// only from SAFE (ACQUIRE, EVALUATE and ARM_MOVING are entered by their commands).
constexpr bool ground_may_request(Mode from, Mode to) {
  if (to == Mode::SAFE) return true;
  if (to == Mode::IDLE) return from == Mode::SAFE;
  return false;
}

}  // namespace petra
