// THE definition of every event: id, severity and text. The text names its
// arguments {0}..{3}; {n:kind} asks ground tools to print a name for the
// number (kind: mode, reason, fc, errc, component, param, step).
// X(NAME, id, SEVERITY, "text")
#pragma once

#include <cstdint>

#include "algo/wire/reasons.hpp"

#define PETRA_EVENTS(X)                                                                       \
  X(BOOT_COMPLETE, 1, INFO,                                                                   \
    "boot complete: {0} bytes allocated at init, arena {1} bytes, {2} parameters from the "   \
    "defaults file")                                                                          \
  X(MODE_CHANGED, 2, INFO, "mode {0:mode} -> {1:mode} (by {2:fc})")                           \
  X(COUNTERS_RESET, 3, INFO, "command, telemetry and fault counters reset")                   \
  X(PARAM_CHANGED, 4, INFO, "parameter {0:param} changed (value in PARAM_VALUE)")             \
  X(ROI_SELECTED, 5, INFO, "ROI x {0}, y {1}, {2} x {3} px selected")                         \
  X(FRAME_ACQUIRED, 6, INFO, "stereo pair {0} acquired ({1} x {2} px, skew {3} us)")          \
  X(CAMERA_FAULT, 7, WARNING, "camera error {0:errc} on pair {1}")                            \
  X(EVAL_STARTED, 8, INFO, "evaluation {0} started on pair {1} (c = {2}, method {3})")        \
  X(EVAL_COMPLETED, 9, INFO, "evaluation {0}: {1} of {2} grind planes in {3} ms")             \
  X(EVAL_FAILED, 10, WARNING, "evaluation {0} failed: {1:errc} in step {2:step}")             \
  X(EVAL_ABORTED, 11, INFO, "evaluation {0} aborted")                                         \
  X(EVAL_TIMEOUT, 12, ERROR, "{2:fc} run {0} exceeded EVAL_TIMEOUT_S ({1} s): aborted, SAFE") \
  X(HEARTBEAT_LOST, 13, ERROR, "component {0:component} silent for {1} ms: SAFE")             \
  X(CYCLE_OVERRUN, 14, WARNING, "loop cycle took {0} us (period {1} us)")                     \
  X(TLM_DROPPED, 15, WARNING, "telemetry queue full: {0} packets dropped so far")             \
  X(CMD_FAILED, 16, WARNING, "command {0:fc} (counter {1}) failed: {2:reason}")               \
  X(COUNTER_STORE_FAILED, 17, WARNING, "could not store the command counter ({0:errc})")      \
  X(FEWER_PLANES, 18, INFO,                                                                   \
    "evaluation {0}: only {1} planes qualified of the {2} asked; the largest refused face: "  \
    "verdict {3} (1 faces away, 2 too small for the tool, 3 too rough over the footprint, "   \
    "4 no support, 6 too uncertain, 7 spans two faces)")                                      \
  X(PRODUCT_SENT, 19, INFO, "product {0} of id {1} queued: {2} chunks, {3} bytes")            \
  X(ARM_READY, 20, INFO, "arm: {0} drives booted and enabled")                                \
  X(ARM_REFUSED, 21, WARNING,                                                                 \
    "arm target refused: reason {0} (1 bad target, 2 beyond reach, 3 inside reach, 4 joint "  \
    "limit, 5 path blocked, 6 bad request), joint {1}, while planning the {2} (0 goto, "      \
    "1 retreat)")                                                                             \
  X(ARM_MOTION_STARTED, 22, INFO, "arm motion started: {0} (0 goto, 1 stow)")                 \
  X(ARM_REACHED, 23, INFO, "arm reached its goal ({0}: 0 goto, 1 stow), tip {1} um off")      \
  X(ARM_VERIFY_FAILED, 24, ERROR,                                                             \
    "arm ended {1} um (tip) off its goal ({0}: 0 goto, 1 stow): pose not verified")           \
  X(ARM_SETTLE_TIMEOUT, 25, ERROR, "arm drives not at target {0} ms after the last one")      \
  X(ARM_DRIVE_FAULT, 26, ERROR,                                                               \
    "arm drive {0} fault {1} (docs/arm.md), detail {2}: drives quick-stopped, SAFE")          \
  X(ARM_EMERGENCY, 27, WARNING, "arm drive {0} emergency, error code {1}")                    \
  X(ARM_CAN_BUS, 28, WARNING, "arm CAN bus {0}: 0 active, 1 warning, 2 passive, 3 off")       \
  X(ARM_BAD_FRAME, 29, WARNING,                                                               \
    "arm drive {0}: malformed or unexpected CAN frame, COB-ID {1}, ignored")                  \
  X(ARM_STOPPED, 30, INFO, "arm quick stop: drives ramped down, holding")                     \
  X(ESTOP_ASSERTED, 31, ERROR, "e-stop input asserted: arm quick stop, SAFE")                 \
  X(CMD_REJECTS_UNREPORTED, 32, WARNING,                                                      \
    "{1} more datagrams rejected for {0:reason} in the last {2} ms: counted, not reported "   \
    "one by one")                                                                             \
  X(UPLINK_NEW_KEY, 33, WARNING,                                                              \
    "new uplink key: command counter window restarted (the old key's last counter was {0})")  \
  X(CMD_KERNEL_DROPS, 34, WARNING,                                                            \
    "command port: {0} datagrams dropped by the kernel (receive buffer full) so far")         \
  X(PRODUCT_REFUSED, 35, WARNING,                                                             \
    "product {0} of id {1} refused: {2} (1 product {0} of id {3} still streaming, 2 too "     \
    "large for its buffer, 3 empty)")                                                         \
  X(PROPOSE_STARTED, 36, INFO,                                                                \
    "proposals {0} started on pair {1}: up to {2}, over {3} (0 the whole image, 1 a region)") \
  X(PROPOSE_COMPLETED, 37, INFO,                                                              \
    "proposals {0}: {1} listed, {2} offering a plane, of {3} rocks detected")                 \
  X(PROPOSE_EMPTY, 38, INFO,                                                                  \
    "proposals {0}: nothing offered: {1:empty} ({2} listed, {3} rocks detected)")             \
  X(PROPOSE_FAILED, 39, WARNING, "proposals {0} failed: {1:errc}")                            \
  X(PROPOSE_ABORTED, 40, INFO, "proposals {0} aborted")                                       \
  X(PROPOSAL_SELECTED, 41, INFO, "proposal {1} of list {0} selected (c = {2})")

// Each rejection reason has its own event, id 0x100 + reason code:
// "command {0:fc} rejected: <reason> (detail {1}, counter {2})", severity WARNING.
#define PETRA_REJECT_EVENT_BASE 0x100

namespace petra {

enum class Severity : std::uint8_t { DEBUG = 0, INFO = 1, WARNING = 2, ERROR = 3, FATAL = 4 };

enum class EventId : std::uint16_t {
#define PETRA_EVENT_ENUM(NAME, id, sev, text) NAME = (id),
  PETRA_EVENTS(PETRA_EVENT_ENUM)
#undef PETRA_EVENT_ENUM
};

struct EventDesc {
  const char* name;
  std::uint16_t id;
  Severity severity;
  const char* text;
};

inline constexpr EventDesc kEventTable[] = {
#define PETRA_EVENT_DESC(NAME, id, sev, text) EventDesc{#NAME, id, Severity::sev, text},
    PETRA_EVENTS(PETRA_EVENT_DESC)
#undef PETRA_EVENT_DESC
#define PETRA_REJECT_EVENT_DESC(NAME, code, desc)                                       \
  EventDesc{"CMD_REJECTED_" #NAME, PETRA_REJECT_EVENT_BASE + (code), Severity::WARNING, \
            "command {0:fc} rejected: " desc " (detail {1}, counter {2})"},
        PETRA_REJECT_REASONS(PETRA_REJECT_EVENT_DESC)
#undef PETRA_REJECT_EVENT_DESC
};

constexpr std::uint16_t rejection_event(Reason r) {
  return static_cast<std::uint16_t>(PETRA_REJECT_EVENT_BASE + static_cast<unsigned>(r));
}

constexpr const EventDesc* find_event(std::uint16_t id) {
  for (const EventDesc& e : kEventTable)
    if (e.id == id) return &e;
  return nullptr;
}

constexpr const char* severity_name(Severity s) {
  switch (s) {
    case Severity::DEBUG:
      return "DEBUG";
    case Severity::INFO:
      return "INFO";
    case Severity::WARNING:
      return "WARNING";
    case Severity::ERROR:
      return "ERROR";
    case Severity::FATAL:
      return "FATAL";
  }
  return "?";
}

}  // namespace petra
