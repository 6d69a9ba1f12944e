// Rock proposals over a whole stereo pair (issue 26): the rocks standing out of
// the ground, each evaluated with the chain (algo/chain/pipeline) and ranked by
// how grindable and how reachable its best face is. The values here are what
// the PROPOSE telecommand asks for and what its telemetry carries; fsw converts
// them at its boundary as it does the grind planes.
// Memory: fixed-size types only; no heap, no I/O.
#pragma once

#include <cstdint>

#include "algo/arm/kinematics.hpp"
#include "algo/core/error.hpp"
#include "algo/core/image_view.hpp"
#include "algo/surface/grind_planes.hpp"

namespace petra {

// Proposals one request may return (the telemetry packet's list length).
inline constexpr int kMaxProposals = 8;
// Grind planes carried per proposal (best first): a rock's 4th grindable,
// reachable face had no slot on 5 of 134 held-out targets with 3 (docs/proposals.md).
inline constexpr int kMaxProposalPlanes = 4;

// How much each term counts in a proposal's score, each in [0, 1], not all 0.
struct ProposalWeights {
  double grindable = 1.0;  // the best plane's verdict and its footprint's flatness
  double reach = 1.0;      // the arm reaches the best plane along its normal
  double certainty = 0.5;  // the best plane's normal and offset 1-sigma
  double size = 0.25;      // the best plane's area against the tool's footprint
};

// What the operator asks of one PROPOSE (original left image pixels).
struct ProposalRequest {
  Rect region;            // where to look; the whole image when empty
  int max_proposals = 4;  // 1..kMaxProposals
  ProposalWeights weights;
};

// A rock found standing out of the ground (step 1: detection).
struct RockCandidate {
  Rect roi;         // original left image pixels, padded around the rock
  int click_u = 0;  // a point on the rock, original left image pixels
  int click_v = 0;
  double height_mm = 0;  // highest point above the fitted ground
  double size_mm = 0;    // largest horizontal extent
  long pixels = 0;       // of the region, at the detection's resolution
};

// Why a proposal's chain run gave no grindable plane, or why it ranks low.
enum class ProposalNote : std::uint8_t {
  ok = 0,
  no_grindable_plane = 1,  // the chain ran; no plane qualified (planes[] say why)
  chain_refused = 2,       // the chain refused the ROI (chain_error says why)
  unreachable = 3,         // planes qualified; the arm reaches none of them
};
const char* proposal_note_name(ProposalNote note);

// The score's terms, each in [0, 1], and their weighted sum.
struct ProposalScore {
  double grindable = 0;
  double reach = 0;
  double certainty = 0;
  double size = 0;
  double total = 0;  // sum of weight * term / sum of weights
};

struct RockProposal {
  RockCandidate rock;
  int planes_c = 0;                       // c the proposer chose for the chain run
  GrindPlane planes[kMaxProposalPlanes];  // accepted first, best first
  int plane_count = 0;
  ProposalNote note = ProposalNote::ok;
  Error chain_error;  // the chain's refusal when note == chain_refused
  // Each accepted plane's approach plan (algo/arm/arm_trajectory plan_approach
  // from the current pose with the arm's standoff); ok = reachable.
  arm::ArmReason reach[kMaxProposalPlanes] = {};
  ProposalScore score;
};

// Ranked best first. An empty list says why in `empty_reason`.
struct ProposalList {
  RockProposal items[kMaxProposals];
  int count = 0;
  int candidates = 0;             // rocks detected before ranking and truncation
  const char* empty_reason = "";  // static text, e.g. "no rock stands out of the ground"
};

}  // namespace petra
