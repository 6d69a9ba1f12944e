// Why a command was rejected or failed: the reason code carried by ACK
// telemetry and by the reason events (tlm/event_defs.hpp gives each rejection
// reason its own event). X(NAME, code, "meaning")
#pragma once

#include <cstdint>

// Rejections: decided before dispatch (cmd/validator) or by the handler before
// it changes anything (BUSY, BAD_TRANSITION). A rejected command changes nothing
// except the rejection counters (and the command counter once authenticated).
#define PETRA_REJECT_REASONS(X)                                                                    \
  X(TOO_SHORT, 1, "datagram shorter than the smallest command packet")                             \
  X(TOO_LONG, 2, "datagram longer than the largest command packet")                                \
  X(BAD_HEADER, 3,                                                                                 \
    "primary header: version, type, secondary header flag, sequence flags or APID wrong")          \
  X(LENGTH_MISMATCH, 4, "packet length field disagrees with the datagram size")                    \
  X(BAD_CRC, 5, "CRC-16-CCITT over the packet does not match")                                     \
  X(BAD_AUTH, 6, "HMAC-SHA256 does not verify: forged, corrupted or signed with another key")      \
  X(REPLAY, 7, "command counter not above the last accepted one: replayed or stale")               \
  X(UNKNOWN_FUNCTION, 8, "function code not defined")                                              \
  X(BAD_PAYLOAD_LENGTH, 9, "argument bytes do not match the command's definition")                 \
  X(OUT_OF_RANGE, 10, "an argument is outside its range (detail: field index)")                    \
  X(INVALID_ARGUMENT, 11,                                                                          \
    "arguments inconsistent: ROI or PROPOSE region outside the image, click outside the ROI, "     \
    "PROPOSE weights all 0, unknown parameter (detail)")                                           \
  X(WRONG_MODE, 12, "command not allowed in the current mode (detail: mode)")                      \
  X(BAD_TRANSITION, 13, "requested mode cannot be entered from the current mode (detail: target)") \
  X(BUSY, 14, "the pipeline worker is still finishing an aborted evaluation or proposal run")      \
  X(ROI_TOO_WIDE, 15, "SELECT_ROI w_px above the memory budget's ROI (detail: the limit, px)")     \
  X(ROI_TOO_TALL, 16, "SELECT_ROI h_px above the memory budget's ROI (detail: the limit, px)")     \
  X(ENVELOPE_TOO_WIDE, 17,                                                                         \
    "SET_PARAM DISP_MIN_PX/DISP_MAX_PX: envelope wider than the memory budget (detail: the "       \
    "limit, disparities = DISP_MAX_PX - DISP_MIN_PX + 1)")

// Failures: an accepted command that could not complete.
#define PETRA_FAIL_REASONS(X)                                                              \
  X(NO_PIPELINE, 32, "this build has no evaluation pipeline")                              \
  X(CAMERA_ERROR, 33, "the camera returned an error (see the CAMERA_FAULT event)")         \
  X(NO_FRAME, 34, "no stereo pair acquired yet; send ACQUIRE or EVALUATE with acquire=1")  \
  X(NO_ROI, 35, "no ROI selected; send SELECT_ROI first")                                  \
  X(PIPELINE_ERROR, 36, "the pipeline returned an error (see the EVAL_FAILED event)")      \
  X(ABORTED, 37, "stopped by ABORT or by entering SAFE")                                   \
  X(ARM_UNAVAILABLE, 38, "no arm is configured in this build")                             \
  X(NO_SUCH_PLANE, 39, "the plane id is not in the last evaluation's result")              \
  X(ARM_REFUSED, 40, "the arm cannot reach the plane (see the ARM_REFUSED event)")         \
  X(ARM_NOT_READY, 41, "the arm's drives are booting, at fault or stopped by a fault")     \
  X(ARM_FAILED, 42, "the motion ended in a drive fault or off its goal (ARM_ events)")     \
  X(NO_SUCH_PROPOSAL, 43,                                                                  \
    "not in the last PROPOSALS list (another proposal_id, a rank beyond its count, or no " \
    "offered plane for ARM_GOTO_PROPOSAL)")                                                \
  X(NO_PROPOSER, 44, "this build's pipeline has no rock proposer")

namespace petra {

enum class Reason : std::uint8_t {
  NONE = 0,
#define PETRA_REASON_ENUM(NAME, code, desc) NAME = (code),
  PETRA_REJECT_REASONS(PETRA_REASON_ENUM) PETRA_FAIL_REASONS(PETRA_REASON_ENUM)
#undef PETRA_REASON_ENUM
};

constexpr const char* reason_name(Reason r) {
  switch (r) {
    case Reason::NONE:
      return "NONE";
#define PETRA_REASON_NAME(NAME, code, desc) \
  case Reason::NAME:                        \
    return #NAME;
      PETRA_REJECT_REASONS(PETRA_REASON_NAME) PETRA_FAIL_REASONS(PETRA_REASON_NAME)
#undef PETRA_REASON_NAME
  }
  return "?";
}

// Acknowledgement stages carried by ACK telemetry.
enum class AckStage : std::uint8_t { ACCEPTED = 1, REJECTED = 2, COMPLETED = 3, FAILED = 4 };

constexpr const char* ack_stage_name(AckStage s) {
  switch (s) {
    case AckStage::ACCEPTED:
      return "ACCEPTED";
    case AckStage::REJECTED:
      return "REJECTED";
    case AckStage::COMPLETED:
      return "COMPLETED";
    case AckStage::FAILED:
      return "FAILED";
  }
  return "?";
}

}  // namespace petra
