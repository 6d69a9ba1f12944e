// THE definition of every telecommand: function code, the modes that allow it,
// its meaning and its arguments with types, units and ranges. Codecs
// (cmd/commands.hpp), validation (cmd/validator), docs/icd.md and
// docs/petra.xtce.xml are all derived from these lists.
//
// X(Name, NAME, function_code, allowed_modes, "meaning", FIELDS)
// FIELDS: F(type, name, count, unit, min, max, "meaning")
#pragma once

#include "algo/wire/field.hpp"
#include "cmd/mode.hpp"

#define PETRA_CMD_U32_MAX 4294967295.0

#define PETRA_SET_PARAM_FIELDS(F)                                             \
  F(u16, param_id, 1, "", 1, 65535, "parameter id (docs/icd.md: parameters)") \
  F(f64, value, 1, "param", -1e9, 1e9, "new value, in the parameter's unit and range")

#define PETRA_GET_PARAM_FIELDS(F) \
  F(u16, param_id, 1, "", 1, 65535, "parameter id; the value returns as PARAM_VALUE telemetry")

#define PETRA_SELECT_ROI_FIELDS(F)                                                           \
  F(u16, x_px, 1, "px", 0, 8191, "ROI left column in the left image")                        \
  F(u16, y_px, 1, "px", 0, 8191, "ROI top row in the left image")                            \
  F(u16, w_px, 1, "px", 8, 8192, "ROI width; the ROI must lie inside the image")             \
  F(u16, h_px, 1, "px", 8, 8192, "ROI height")                                               \
  F(u8, planes, 1, "", 1, 8, "c: number of grind planes the operator sees (usually 2 or 3)") \
  F(u8, has_click, 1, "bool", 0, 1, "1 when a point on the rock was clicked")                \
  F(u16, click_u_px, 1, "px", 0, 8191, "clicked column (inside the ROI when has_click)")     \
  F(u16, click_v_px, 1, "px", 0, 8191, "clicked row (inside the ROI when has_click)")

#define PETRA_EVALUATE_FIELDS(F) \
  F(u8, acquire, 1, "bool", 0, 1, "1: take a new stereo pair first; 0: use the last pair")

#define PETRA_ARM_GOTO_FIELDS(F)                                                          \
  F(u8, plane_rank, 1, "", 0, 7, "grind plane by rank in the last evaluation (0 = best)") \
  F(f32, standoff_mm, 1, "mm", 0, 300, "approach waypoint distance along the plane normal")

// The region is in left image pixels; 0, 0, 0, 0 asks for the whole image.
// The weights say how much each term counts in a proposal's score (not all 0).
#define PETRA_PROPOSE_FIELDS(F)                                                                  \
  F(u8, acquire, 1, "bool", 0, 1, "1: take a new stereo pair first; 0: use the last pair")       \
  F(u16, x_px, 1, "px", 0, 8191, "region left column (0 with w_px = h_px = 0: the whole image)") \
  F(u16, y_px, 1, "px", 0, 8191, "region top row")                                               \
  F(u16, w_px, 1, "px", 0, 8192, "region width: 0 (whole image) or 32.. inside the image")       \
  F(u16, h_px, 1, "px", 0, 8192, "region height: 0 (whole image) or 32.. inside the image")      \
  F(u8, count, 1, "", 1, 8, "proposals wanted, best first (at most kMaxProposals = 8)")          \
  F(f32, weight_grindable, 1, "1", 0, 1, "score weight: the best plane's verdict and flatness")  \
  F(f32, weight_reach, 1, "1", 0, 1, "score weight: the arm reaches the plane along its normal") \
  F(f32, weight_certainty, 1, "1", 0, 1, "score weight: the plane's normal and offset 1-sigma")  \
  F(f32, weight_size, 1, "1", 0, 1, "score weight: the plane's area against the tool footprint")

#define PETRA_SELECT_PROPOSAL_FIELDS(F)                                                  \
  F(u32, proposal_id, 1, "", 1, PETRA_CMD_U32_MAX, "the PROPOSALS packet's proposal_id") \
  F(u8, rank, 1, "", 1, 8, "proposal by rank in that list (1 = best)")

#define PETRA_ARM_GOTO_PROPOSAL_FIELDS(F)                                                      \
  F(u32, proposal_id, 1, "", 1, PETRA_CMD_U32_MAX, "the PROPOSALS packet's proposal_id")       \
  F(u8, rank, 1, "", 1, 8, "proposal by rank in that list (1 = best); its best offered plane") \
  F(f32, standoff_mm, 1, "mm", 0, 300, "approach waypoint distance along the plane normal")

#define PETRA_ARM_GOTO_PROPOSAL_PLANE_FIELDS(F)                                                 \
  F(u32, proposal_id, 1, "", 1, PETRA_CMD_U32_MAX, "the PROPOSALS packet's proposal_id")        \
  F(u8, rank, 1, "", 1, 8, "proposal by rank in that list (1 = best)")                          \
  F(u8, plane, 1, "", 1, 4, "its plane by PROPOSAL_PLANES' order (1 = first); must be offered") \
  F(f32, standoff_mm, 1, "mm", 0, 300, "approach waypoint distance along the plane normal")

#define PETRA_SET_MODE_FIELDS(F) \
  F(u8, mode, 1, "enum", 0, 5, "target mode: 1 IDLE (only from SAFE) or 5 SAFE (from any mode)")

#define PETRA_COMMANDS(X)                                                                         \
  X(Noop, NOOP, 0x01, ::petra::kInAnyMode, "do nothing; proves the uplink and counters",          \
    PETRA_NO_FIELDS)                                                                              \
  X(ResetCounters, RESET_COUNTERS, 0x02, ::petra::kInAnyMode,                                     \
    "zero the command, telemetry and fault counters", PETRA_NO_FIELDS)                            \
  X(SetParam, SET_PARAM, 0x03, ::petra::kInAnyMode, "set one parameter", PETRA_SET_PARAM_FIELDS)  \
  X(GetParam, GET_PARAM, 0x04, ::petra::kInAnyMode, "report one parameter",                       \
    PETRA_GET_PARAM_FIELDS)                                                                       \
  X(DumpParams, DUMP_PARAMS, 0x05, ::petra::kInAnyMode,                                           \
    "report every parameter as PARAM_VALUE packets", PETRA_NO_FIELDS)                             \
  X(SelectRoi, SELECT_ROI, 0x10, ::petra::kInIdle,                                                \
    "choose the rock: ROI, plane count c and optional click, for the next EVALUATE",              \
    PETRA_SELECT_ROI_FIELDS)                                                                      \
  X(Acquire, ACQUIRE, 0x11, ::petra::kInIdle, "take a stereo pair (and downlink the left image)", \
    PETRA_NO_FIELDS)                                                                              \
  X(Evaluate, EVALUATE, 0x12, ::petra::kInIdle,                                                   \
    "run the pipeline on the selected ROI; grind planes return as telemetry",                     \
    PETRA_EVALUATE_FIELDS)                                                                        \
  X(Propose, PROPOSE, 0x13, ::petra::kInIdle,                                                     \
    "find and rank the grindable rocks in a region of the pair; PROPOSALS returns as telemetry",  \
    PETRA_PROPOSE_FIELDS)                                                                         \
  X(SelectProposal, SELECT_PROPOSAL, 0x14, ::petra::kInIdle,                                      \
    "choose a proposal's ROI, click and c for the next EVALUATE, with SELECT_ROI's checks",       \
    PETRA_SELECT_PROPOSAL_FIELDS)                                                                 \
  X(ArmGoto, ARM_GOTO, 0x20, ::petra::kInIdle,                                                    \
    "move the grinder to a grind plane of the last evaluation", PETRA_ARM_GOTO_FIELDS)            \
  X(ArmGotoProposal, ARM_GOTO_PROPOSAL, 0x22, ::petra::kInIdle,                                   \
    "move the grinder to a proposal's best offered plane, with ARM_GOTO's checks",                \
    PETRA_ARM_GOTO_PROPOSAL_FIELDS)                                                               \
  X(ArmGotoProposalPlane, ARM_GOTO_PROPOSAL_PLANE, 0x23, ::petra::kInIdle,                        \
    "move the grinder to one offered plane of a proposal (PROPOSAL_PLANES), with ARM_GOTO's "     \
    "checks",                                                                                     \
    PETRA_ARM_GOTO_PROPOSAL_PLANE_FIELDS)                                                         \
  X(ArmStow, ARM_STOW, 0x21, ::petra::kInIdleOrSafe, "move the arm to its stowed pose",           \
    PETRA_NO_FIELDS)                                                                              \
  X(Abort, ABORT, 0x30, ::petra::kInAnyMode,                                                      \
    "stop the running evaluation or arm motion; back to IDLE", PETRA_NO_FIELDS)                   \
  X(SetMode, SET_MODE, 0x31, ::petra::kInAnyMode, "request a mode change", PETRA_SET_MODE_FIELDS)
