// THE definition of every telemetry packet: APID, meaning and fields with
// types, units and ranges. Codecs (tlm/telemetry.hpp), docs/icd.md and
// docs/petra.xtce.xml are derived from these lists.
//
// X(Name, NAME, apid, "meaning", FIELDS)
// FIELDS: F(type, name, count, unit, min, max, "meaning")
#pragma once

#include "algo/wire/field.hpp"

#define PETRA_U32_MAX 4294967295.0

// Pipeline steps whose times housekeeping and EVAL_RESULT carry (index = slot).
#define PETRA_PIPELINE_STEPS(X) \
  X(ACQUIRE, 0)                 \
  X(RECTIFY, 1)                 \
  X(SHADOW, 2)                  \
  X(MATCH, 3)                   \
  X(RECONSTRUCT, 4)             \
  X(SEGMENT, 5)                 \
  X(PLANES, 6)                  \
  X(PRODUCTS, 7)
#define PETRA_STEP_SLOTS 8

#define PETRA_HK_FIELDS(F)                                                                       \
  F(u8, mode, 1, "enum", 0, 5, "current mode (docs/executive.md)")                               \
  F(u32, uptime_s, 1, "s", 0, PETRA_U32_MAX, "time since boot")                                  \
  F(u32, cycles, 1, "", 0, PETRA_U32_MAX, "loop cycles since boot")                              \
  F(u32, cycle_overruns, 1, "", 0, PETRA_U32_MAX, "cycles that took longer than the period")     \
  F(u32, max_cycle_us, 1, "us", 0, PETRA_U32_MAX, "longest cycle since the counters were reset") \
  F(u32, cmd_received, 1, "", 0, PETRA_U32_MAX, "datagrams received on the command port")        \
  F(u32, cmd_accepted, 1, "", 0, PETRA_U32_MAX, "commands that passed validation")               \
  F(u32, cmd_rejected, 1, "", 0, PETRA_U32_MAX, "datagrams rejected (see cmd_unreported)")       \
  F(u32, cmd_completed, 1, "", 0, PETRA_U32_MAX, "accepted commands that completed")             \
  F(u32, cmd_failed, 1, "", 0, PETRA_U32_MAX, "accepted commands that failed")                   \
  F(u32, last_counter, 1, "", 0, PETRA_U32_MAX, "last authenticated command counter")            \
  F(u8, last_function_code, 1, "", 0, 255, "function code of the last command seen")             \
  F(u8, last_reason, 1, "enum", 0, 255, "reason of the last rejection or failure")               \
  F(u32, cmd_unreported, 1, "", 0, PETRA_U32_MAX,                                                \
    "rejections without their own event and ack (throttled: CMD_REJECTS_UNREPORTED)")            \
  F(u32, cmd_kernel_drops, 1, "", 0, PETRA_U32_MAX,                                              \
    "command datagrams the kernel dropped: receive buffer full (SO_RXQ_OVFL)")                   \
  F(u32, tlm_sent, 1, "", 0, PETRA_U32_MAX, "telemetry packets sent")                            \
  F(u32, tlm_dropped, 1, "", 0, PETRA_U32_MAX, "telemetry packets dropped: queue full")          \
  F(u32, tlm_send_errors, 1, "", 0, PETRA_U32_MAX, "telemetry packets the socket refused")       \
  F(u16, tlm_queue_high_water, 1, "", 0, 65535, "most packets waiting in the queue")             \
  F(u32, events, 1, "", 0, PETRA_U32_MAX, "events raised since boot")                            \
  F(u32, faults, 1, "", 0, PETRA_U32_MAX, "faults (heartbeat lost, timeouts) since boot")        \
  F(u32, memory_bytes, 1, "bytes", 0, PETRA_U32_MAX, "memory allocated at init (all budgets)")   \
  F(u32, arena_bytes, 1, "bytes", 0, PETRA_U32_MAX, "pipeline arena capacity")                   \
  F(u32, arena_high_water_bytes, 1, "bytes", 0, PETRA_U32_MAX, "most arena bytes ever in use")   \
  F(u32, frames, 1, "", 0, PETRA_U32_MAX, "stereo pairs acquired")                               \
  F(u32, evaluations, 1, "", 0, PETRA_U32_MAX, "evaluations started")                            \
  F(u8, eval_running, 1, "bool", 0, 1, "1 while the pipeline worker is busy")                    \
  F(u32, eval_elapsed_ms, 1, "ms", 0, PETRA_U32_MAX,                                             \
    "time spent in the running or last evaluation")                                              \
  F(u32, step_us, PETRA_STEP_SLOTS, "us", 0, PETRA_U32_MAX,                                      \
    "time per pipeline step of the last evaluation (ACQUIRE, RECTIFY, SHADOW, MATCH, "           \
    "RECONSTRUCT, SEGMENT, PLANES, PRODUCTS)")

#define PETRA_ARM_STATUS_FIELDS(F)                                                                 \
  F(u8, state, 1, "enum", 0, 9,                                                                    \
    "0 off, 1 booting, 2 enabling, 3 holding, 4 moving, 5 approaching, 6 retreating, 7 settling, " \
    "8 stopped, 9 fault (docs/arm.md)")                                                            \
  F(u8, progress, 1, "enum", 0, 3, "0 idle, 1 moving, 2 reached, 3 failed")                        \
  F(f32, joint_deg, 5, "deg", -360, 360, "measured joint angles th1..th5 (drive feedback)")        \
  F(f32, target_deg, 5, "deg", -360, 360, "last set-point of each joint")                          \
  F(f64, tip_mm, 3, "mm", -1e7, 1e7, "grinder tip from the measured joints, world frame")          \
  F(f64, axis, 3, "1", -1, 1, "tool axis (unit, into the work), world frame")                      \
  F(u8, refusal, 1, "enum", 0, 6,                                                                  \
    "last refusal: 0 none, 1 bad target, 2 beyond reach, 3 inside reach, 4 joint limit, "          \
    "5 path blocked, 6 bad request")                                                               \
  F(u8, refusal_joint, 1, "", 0, 5, "joint of a joint-limit refusal, 1..5 (0: none)")              \
  F(f32, tip_error_mm, 1, "mm", 0, 1e7, "last verification: tip to the plane centroid")            \
  F(f32, axis_error_deg, 1, "deg", 0, 180, "last verification: tool axis to -normal")              \
  F(u8, fault_node, 1, "", 0, 127, "drive (CANopen node) at fault, 0 none")                        \
  F(u8, fault, 1, "enum", 0, 12, "its fault (docs/arm.md fault table)")                            \
  F(u32, fault_detail, 1, "", 0, PETRA_U32_MAX, "EMCY code, SDO abort code or statusword")         \
  F(u8, drive_state, 5, "enum", 0, 8,                                                              \
    "per drive: 0 idle, 1 resetting, 2 configuring, 3 starting, 4 operational, 5 enabling, "       \
    "6 ready, 7 quick stopped, 8 fault")                                                           \
  F(u8, bus_state, 1, "enum", 0, 3, "CAN controller: 0 error active, 1 warning, 2 passive, 3 off") \
  F(u32, moves_completed, 1, "", 0, PETRA_U32_MAX, "motions reached and verified since boot")      \
  F(u32, can_sent, 1, "", 0, PETRA_U32_MAX, "CAN frames sent by the master")                       \
  F(u32, can_received, 1, "", 0, PETRA_U32_MAX, "CAN frames received by the master")               \
  F(u32, can_bad_frames, 1, "", 0, PETRA_U32_MAX, "frames from the drives that failed validation") \
  F(u32, can_send_errors, 1, "", 0, PETRA_U32_MAX, "frames the CAN port refused")

#define PETRA_EVENT_FIELDS(F)                                                      \
  F(u16, event_id, 1, "enum", 0, 65535, "event id (docs/icd.md: events)")          \
  F(u8, severity, 1, "enum", 0, 4, "0 DEBUG, 1 INFO, 2 WARNING, 3 ERROR, 4 FATAL") \
  F(i32, args, 4, "", -2147483648.0, 2147483647.0, "arguments of the event text")

#define PETRA_ACK_FIELDS(F)                                                                 \
  F(u8, function_code, 1, "", 0, 255, "function code of the command (0: not readable)")     \
  F(u32, counter, 1, "", 0, PETRA_U32_MAX, "its command counter (0 before authentication)") \
  F(u8, stage, 1, "enum", 1, 4, "1 ACCEPTED, 2 REJECTED, 3 COMPLETED, 4 FAILED")            \
  F(u8, reason, 1, "enum", 0, 255, "reason code when REJECTED or FAILED (docs/icd.md)")     \
  F(u16, detail, 1, "", 0, 65535, "field index, mode or parameter id, per reason")

#define PETRA_PARAM_VALUE_FIELDS(F)                 \
  F(u16, param_id, 1, "", 1, 65535, "parameter id") \
  F(f64, value, 1, "param", -1e9, 1e9, "current value, in the parameter's unit")

#define PETRA_EVAL_RESULT_FIELDS(F)                                                               \
  F(u32, eval_id, 1, "", 0, PETRA_U32_MAX, "evaluation number since boot")                        \
  F(u32, frame, 1, "", 0, PETRA_U32_MAX, "stereo pair it ran on")                                 \
  F(u8, status, 1, "enum", 0, 3, "0 all c planes, 1 fewer planes qualified, 2 failed, 3 aborted") \
  F(u8, reason, 1, "enum", 0, 255, "failure reason when status is 2 or 3")                        \
  F(u16, roi_px, 4, "px", 0, 8192, "ROI x, y, w, h in the left image")                            \
  F(u8, planes_requested, 1, "", 0, 8, "the operator's c")                                        \
  F(u8, planes_found, 1, "", 0, 8, "grind planes that qualified (GRIND_PLANE packets follow)")    \
  F(u32, dense_points, 1, "", 0, PETRA_U32_MAX, "3D points before the mean filter")               \
  F(u32, filtered_points, 1, "", 0, PETRA_U32_MAX, "3D points after the mean filter")             \
  F(f32, disparity_min, 1, "px", -1e6, 1e6, "smallest disparity found in the ROI")                \
  F(f32, disparity_max, 1, "px", -1e6, 1e6, "largest disparity found in the ROI")                 \
  F(u32, total_ms, 1, "ms", 0, PETRA_U32_MAX, "wall time of the evaluation")                      \
  F(u32, step_us, PETRA_STEP_SLOTS, "us", 0, PETRA_U32_MAX,                                       \
    "time per pipeline step (as housekeeping)")                                                   \
  F(u8, segmentation, 1, "enum", 0, 1,                                                            \
    "how the rock was segmented: 0 above the ground plane, 1 grown from the click (no ground)")   \
  F(f32, calib_vertical_offset_px, 1, "px", -100, 100,                                            \
    "calibration check: median row offset of matched features, right minus left")                 \
  F(f32, calib_spread_px, 1, "px", 0, 100, "calibration check: 1.4826 x MAD of the row offsets")  \
  F(u16, calib_features, 1, "", 0, 4096, "calibration check: matched features kept")              \
  F(u8, calib_verdict, 1, "enum", 0, 3,                                                           \
    "calibration check: 0 unknown, 1 ok, 2 drifted, 3 drifted and corrected (right view's rows "  \
    "moved by the offset before matching)")                                                       \
  F(f32, gray_gain, 1, "1", 0.25, 4,                                                              \
    "matcher's map of the right view's gray levels, level = gain v + offset: gain (1: the "       \
    "cameras agree or the map was not measured)")                                                 \
  F(f32, gray_offset, 1, "DN", -1024, 1024,                                                       \
    "matcher's map of the right view's gray levels: offset (0: the cameras agree)")               \
  F(u8, click_loosened, 1, "", 0, 2,                                                              \
    "rock grown from the click: times its concave limit was doubled, the first growth holding "   \
    "under 5 % of the ROI's points (a groove under the click; 0 otherwise)")

#define PETRA_GRIND_PLANE_FIELDS(F)                                                      \
  F(u32, eval_id, 1, "", 0, PETRA_U32_MAX, "evaluation it belongs to")                   \
  F(u8, rank, 1, "", 0, 7, "0 = best")                                                   \
  F(u8, plane_count, 1, "", 0, 8, "planes in this evaluation")                           \
  F(f64, normal, 3, "1", -1, 1, "unit normal, out of the rock, calibration world frame") \
  F(f64, centroid_mm, 3, "mm", -1e7, 1e7,                                                \
    "where the grinder goes: the footprint disc's centre, on the surface")               \
  F(f64, area_mm2, 1, "mm2", 0, 1e12, "supporting area")                                 \
  F(f64, flatness_rms_mm, 1, "mm", 0, 1e6, "RMS distance of its points to the plane")    \
  F(u32, triangles, 1, "", 0, PETRA_U32_MAX, "mesh triangles supporting it")             \
  F(u8, verdict, 1, "enum", 0, 7,                                                        \
    "0 grindable (only grindable planes are sent; docs/reconstruction.md)")              \
  F(u8, plane_source, 1, "enum", 0, 1,                                                   \
    "0 the face's whole-patch plane, 1 the footprint disc's own (the face curves)")      \
  F(f32, normal_sigma_deg, 1, "deg", 0, 180, "normal 1-sigma (RMS angle), noise model")  \
  F(f32, offset_sigma_mm, 1, "mm", 0, 1e6, "offset 1-sigma along the normal")            \
  F(f32, footprint_rms_mm, 1, "mm", 0, 1e6, "flatness (RMS) over the footprint disc")    \
  F(f32, footprint_diameter_mm, 1, "mm", 0, 1000, "grinder footprint it was judged for") \
  F(u8, footprint_reach, 1, "enum", 0, 3,                                                \
    "0 no arm asked, 1 the most level flat disc (reached), 2 moved: the most level is "  \
    "out of the arm's reach, this is the most level it reaches, 3 no flat disc reached")

#define PETRA_GROUND_PLANE_FIELDS(F)                                        \
  F(u32, eval_id, 1, "", 0, PETRA_U32_MAX, "evaluation it belongs to")      \
  F(f64, normal, 3, "1", -1, 1, "unit normal (n . X + d = 0, world frame)") \
  F(f64, d_mm, 1, "mm", -1e7, 1e7, "plane offset")                          \
  F(u32, points, 1, "", 0, PETRA_U32_MAX, "3D points classified as ground")

// PROPOSALS: one packet per PROPOSE run, the ranked list as parallel arrays
// of PETRA_MAX_PROPOSALS slots (slot i = rank i + 1; slots from `count` on are
// 0). The plane shown per proposal is its best offered one (verdict grindable,
// reach ok) when it has one (plane_offered 1), else its first plane (verdict
// and reach say why it is not offered); none when plane_count is 0.
// A proposal's plane as parallel arrays of N slots: PROPOSALS (the plane
// shown, one per proposal) and PROPOSAL_PLANES (every carried plane) share it.
#define PETRA_PLANE_SLOT_FIELDS(F, N, WHAT)                                                        \
  F(f32, normal, 3 * (N), "1", -1, 1, WHAT "unit normal out of the rock, calibration world frame") \
  F(f32, centroid_mm, 3 * (N), "mm", -1e7, 1e7, WHAT "where the grinder goes, world frame")        \
  F(f32, area_mm2, N, "mm2", 0, 1e12, WHAT "supporting area")                                      \
  F(f32, normal_sigma_deg, N, "deg", 0, 180, WHAT "normal 1-sigma")                                \
  F(f32, offset_sigma_mm, N, "mm", 0, 1e6, WHAT "offset 1-sigma")                                  \
  F(u8, verdict, N, "enum", 0, 7,                                                                  \
    WHAT                                                                                           \
    "0 grindable, 1 faces away, 2 too small, 3 too rough, 4 no support, 5 surplus, "               \
    "6 too uncertain, 7 spans two faces")                                                          \
  F(u8, reach, N, "enum", 0, 6,                                                                    \
    WHAT                                                                                           \
    "arm reach, 0 ok, 1 bad target, 2 beyond reach, 3 inside reach, 4 joint "                      \
    "limit, 5 path blocked, 6 bad request (ARM_STATUS refusal)")

#define PETRA_MAX_PROPOSALS 8
#define PETRA_PROPOSAL_EMPTY_REASONS(X)                                                \
  X(NONE, 0, "at least one proposal offers a plane")                                   \
  X(NO_ROCK, 1, "no rock stands out of the ground in the region")                      \
  X(NONE_KEPT, 2, "rocks were detected but none could be proposed")                    \
  X(NONE_GRINDABLE, 3, "the proposals listed have no grindable plane (notes say why)") \
  X(NONE_REACHABLE, 4, "grindable planes were found; the arm reaches none of them")    \
  X(FAILED, 5, "the run failed (reason)")
#define PETRA_PROPOSALS_FIELDS(F)                                                                  \
  F(u32, proposal_id, 1, "", 0, PETRA_U32_MAX, "PROPOSE run number since boot")                    \
  F(u32, frame, 1, "", 0, PETRA_U32_MAX, "stereo pair it ran on")                                  \
  F(u8, status, 1, "enum", 0, 2,                                                                   \
    "0 proposals, 1 nothing offered (empty_reason), 2 failed (an aborted run sends nothing)")      \
  F(u8, reason, 1, "enum", 0, 255, "failure reason when status is 2")                              \
  F(u8, empty_reason, 1, "enum", 0, 5,                                                             \
    "0 none, 1 no rock, 2 none kept, 3 none grindable, 4 none reachable, 5 failed")                \
  F(u8, count, 1, "", 0, PETRA_MAX_PROPOSALS, "proposals in the list")                             \
  F(u16, candidates, 1, "", 0, 65535, "rocks detected before ranking and truncation")              \
  F(u16, region_px, 4, "px", 0, 8192, "region x, y, w, h searched (the whole image: 0, 0, W, H)")  \
  F(u32, total_ms, 1, "ms", 0, PETRA_U32_MAX, "wall time of the run")                              \
  F(u8, picture_step, 1, "", 0, 16,                                                                \
    "the picture (PRODUCT 5, same id): left image px = picture px x step (0: no picture)")         \
  F(u8, rank, PETRA_MAX_PROPOSALS, "", 0, PETRA_MAX_PROPOSALS, "1 = best; 0: empty slot")          \
  F(u16, roi_px, 4 * PETRA_MAX_PROPOSALS, "px", 0, 8192,                                           \
    "per proposal: ROI x, y, w, h in the left image (what SELECT_PROPOSAL selects)")               \
  F(u16, click_px, 2 * PETRA_MAX_PROPOSALS, "px", 0, 8191, "per proposal: click u, v on the rock") \
  F(f32, height_mm, PETRA_MAX_PROPOSALS, "mm", 0, 1e6, "rock's highest point above the ground")    \
  F(f32, size_mm, PETRA_MAX_PROPOSALS, "mm", 0, 1e6, "rock's largest horizontal extent")           \
  F(u8, planes_c, PETRA_MAX_PROPOSALS, "", 0, 8, "c the proposer chose for the chain run")         \
  F(u8, note, PETRA_MAX_PROPOSALS, "enum", 0, 3,                                                   \
    "0 ok, 1 no grindable plane, 2 chain refused, 3 unreachable")                                  \
  F(u8, plane_count, PETRA_MAX_PROPOSALS, "", 0, 3, "planes the proposal carries on board")        \
  F(u8, plane_offered, PETRA_MAX_PROPOSALS, "bool", 0, 1,                                          \
    "1: the plane shown is offered (grindable and reached; ARM_GOTO_PROPOSAL's target)")           \
  F(f32, score_total, PETRA_MAX_PROPOSALS, "1", 0, 1,                                              \
    "weighted sum of the terms / sum of weights")                                                  \
  F(f32, score_grindable, PETRA_MAX_PROPOSALS, "1", 0, 1, "score term: grindable")                 \
  F(f32, score_reach, PETRA_MAX_PROPOSALS, "1", 0, 1, "score term: reach")                         \
  F(f32, score_certainty, PETRA_MAX_PROPOSALS, "1", 0, 1, "score term: certainty")                 \
  F(f32, score_size, PETRA_MAX_PROPOSALS, "1", 0, 1, "score term: size")                           \
  PETRA_PLANE_SLOT_FIELDS(F, PETRA_MAX_PROPOSALS, "plane shown: ")

#define PETRA_PRODUCT_DATA_BYTES 1024
#define PETRA_PRODUCT_FIELDS(F)                                                                  \
  F(u8, product, 1, "enum", 1, 5,                                                                \
    "1 LEFT_IMAGE, 2 DISPARITY, 3 OVERLAY, 4 POINT_CLOUD, 5 PROPOSALS (the picture)")            \
  F(u8, format, 1, "enum", 1, 3, "1 gray8 rows, 2 rgb8 rows, 3 xyz f32 mm triples (big-endian)") \
  F(u32, id, 1, "", 0, PETRA_U32_MAX, "frame (LEFT_IMAGE), evaluation id or proposal_id")        \
  F(u16, chunk, 1, "", 0, 65535, "chunk index, 0 first")                                         \
  F(u16, chunks, 1, "", 1, 65535, "chunks in the product")                                       \
  F(u32, total_bytes, 1, "bytes", 0, PETRA_U32_MAX, "product size")                              \
  F(u16, width, 1, "px", 0, 65535, "image width (point cloud: points)")                          \
  F(u16, height, 1, "px", 0, 65535, "image height (point cloud: 1)")                             \
  F(u16, data_len, 1, "bytes", 0, PETRA_PRODUCT_DATA_BYTES, "bytes of data used in this chunk")  \
  F(u8, data, PETRA_PRODUCT_DATA_BYTES, "", 0, 255, "product bytes [chunk*1024, +data_len)")

// PROPOSAL_PLANES: follows each PROPOSALS packet of a finished run (same
// proposal_id): every plane each proposal carries on board, not only the one
// PROPOSALS shows, as parallel arrays of PETRA_MAX_PROPOSALS x
// PETRA_MAX_PROPOSAL_PLANES = P slots (slot P i + j = plane j + 1 of rank i + 1;
// slots from plane_count on are 0). ARM_GOTO_PROPOSAL_PLANE takes any offered one.
#define PETRA_MAX_PROPOSAL_PLANES 4
#define PETRA_PROPOSAL_PLANE_SLOTS (PETRA_MAX_PROPOSALS * PETRA_MAX_PROPOSAL_PLANES)
#define PETRA_PROPOSAL_PLANES_FIELDS(F)                                              \
  F(u32, proposal_id, 1, "", 0, PETRA_U32_MAX, "the PROPOSALS packet's proposal_id") \
  F(u32, frame, 1, "", 0, PETRA_U32_MAX, "stereo pair it ran on")                    \
  F(u8, count, 1, "", 0, PETRA_MAX_PROPOSALS, "proposals in the list")               \
  F(u8, plane_count, PETRA_MAX_PROPOSALS, "", 0, PETRA_MAX_PROPOSAL_PLANES,          \
    "per proposal: planes it carries on board")                                      \
  F(u8, offered, PETRA_PROPOSAL_PLANE_SLOTS, "bool", 0, 1,                           \
    "1: grindable and reached (ARM_GOTO_PROPOSAL_PLANE's target)")                   \
  PETRA_PLANE_SLOT_FIELDS(F, PETRA_PROPOSAL_PLANE_SLOTS, "")

#define PETRA_TELEMETRY(X)                                                                       \
  X(Housekeeping, HK, 0x010, "housekeeping: mode, counters, memory, loop and pipeline timing",   \
    PETRA_HK_FIELDS)                                                                             \
  X(Event, EVENT, 0x011, "an event: id, severity, four arguments (text in docs/icd.md)",         \
    PETRA_EVENT_FIELDS)                                                                          \
  X(Ack, ACK, 0x012, "command acknowledgement: accepted, rejected, completed or failed",         \
    PETRA_ACK_FIELDS)                                                                            \
  X(ParamValue, PARAM_VALUE, 0x013, "one parameter's value (GET_PARAM, DUMP_PARAMS, SET_PARAM)", \
    PETRA_PARAM_VALUE_FIELDS)                                                                    \
  X(ArmStatus, ARM_STATUS, 0x014,                                                                \
    "arm: state, joints, tool pose, last refusal and verification, drive faults, CAN counters",  \
    PETRA_ARM_STATUS_FIELDS)                                                                     \
  X(EvalResult, EVAL_RESULT, 0x020, "summary of one evaluation; its planes follow",              \
    PETRA_EVAL_RESULT_FIELDS)                                                                    \
  X(GrindPlane, GRIND_PLANE, 0x021, "one ranked grind plane", PETRA_GRIND_PLANE_FIELDS)          \
  X(GroundPlane, GROUND_PLANE, 0x022, "the ground plane of one evaluation",                      \
    PETRA_GROUND_PLANE_FIELDS)                                                                   \
  X(Proposals, PROPOSALS, 0x023, "the ranked rock proposals of one PROPOSE run",                 \
    PETRA_PROPOSALS_FIELDS)                                                                      \
  X(ProposalPlanes, PROPOSAL_PLANES, 0x024,                                                      \
    "every plane each proposal of one PROPOSE run carries (PROPOSALS shows one)",                \
    PETRA_PROPOSAL_PLANES_FIELDS)                                                                \
  X(Product, PRODUCT, 0x030,                                                                     \
    "one chunk of a product (image or point cloud); sequence flags mark first/last chunk",       \
    PETRA_PRODUCT_FIELDS)
