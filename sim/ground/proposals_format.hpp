// The PROPOSALS and PROPOSAL_PLANES packets in the operator's words (`petra tlm`, the ground
// station's line): a summary, then one line per proposal with its ROI, click,
// rock, c, note, score and terms, and the plane shown with its verdict and
// reach. Names come from the packet definition (tlm/tlm_defs.hpp) and algo's
// stable keys (verdict_key, arm_reason_name).
#pragma once

#include <cstdint>
#include <string>

#include "tlm/telemetry.hpp"

namespace petra::ground {

// "no_rock", "none_grindable", ... of PROPOSALS empty_reason (lower case).
std::string proposal_empty_name(long code);
// A note's key ("ok", "no_grindable_plane", ...): algo's proposal_note_name.
const char* proposal_note_key(std::uint8_t note);
// The summary and one indented line per proposal (no trailing newline).
std::string format_proposals(const tlm::Proposals& p);
// PROPOSAL_PLANES: a summary, then one indented line per carried plane
// ("#rank.plane offered|not offered: normal, centroid, area, sigma, verdict, reach").
std::string format_proposal_planes(const tlm::ProposalPlanes& p);

}  // namespace petra::ground
