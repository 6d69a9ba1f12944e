// The operator's pick of a rock proposal on the ground station: which
// proposal of the last PROPOSALS packet a point of the left image falls in,
// and the command that takes it: SELECT_PROPOSAL (proposal_id, rank; the
// board checks the list is still its last one and applies SELECT_ROI's
// checks to the proposal's ROI) or, equivalently, SELECT_ROI with the
// proposal's ROI, click and c as listed.
//   POST /api/proposals/pick {"u":U,"v":V} or {"rank":K} [,"as":"select_roi"]
// Also the page's names for a PROPOSALS packet (notes, verdicts, reaches).
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "algo/core/result.hpp"
#include "cmd/commands.hpp"
#include "tlm/telemetry.hpp"

namespace petra::gnd {

enum class PickAs { SELECT_PROPOSAL, SELECT_ROI };

// Rank (1 = best) of the best-ranked listed proposal whose ROI holds (u, v)
// (original left image px); nullopt when none does.
std::optional<int> proposal_at(const tlm::Proposals& list, double u, double v);

// The command taking proposal `rank` of the list; an error naming the rank
// when it is not listed.
Result<cmd::Command> pick_command(const tlm::Proposals& list, int rank, PickAs as);

// The pick request's body parsed against the list: {"u","v"} or {"rank"},
// optional "as": "select_proposal" (default) | "select_roi". Errors name the member.
Result<cmd::Command> parse_pick_request(std::string_view body, const tlm::Proposals* list);

// {"empty_reason":"..","notes":[..],"verdicts":[..],"reaches":[..]} for the page.
std::string proposals_names_json(const tlm::Proposals& list);

}  // namespace petra::gnd
