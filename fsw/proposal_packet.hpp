// The rock proposals at the algo/fsw boundary: the one conversion of a
// ProposalList (algo/propose/proposals.hpp) to its PROPOSALS packet, and the
// questions the executive asks of a proposal (the plane it offers, the
// selection it makes). Memory: none; no heap.
#pragma once

#include <cstdint>
#include <string_view>

#include "algo/propose/proposals.hpp"
#include "cmd/commands.hpp"
#include "tlm/telemetry.hpp"

namespace petra::fsw {

static_assert(PETRA_MAX_PROPOSALS == kMaxProposals, "the PROPOSALS packet holds the whole list");

enum class ProposalEmpty : std::uint8_t {
#define PETRA_EMPTY_ENUM(NAME, code, desc) NAME = (code),
  PETRA_PROPOSAL_EMPTY_REASONS(PETRA_EMPTY_ENUM)
#undef PETRA_EMPTY_ENUM
};

static_assert(PETRA_MAX_PROPOSAL_PLANES == kMaxProposalPlanes,
              "PROPOSAL_PLANES holds every plane a proposal carries");

// ARM_GOTO_PROPOSAL_PLANE's `plane` field ranges over exactly those slots.
constexpr double command_plane_max() {
  for (const wire::FieldDesc& f : cmd::ArmGotoProposalPlaneArgs::fields())
    if (std::string_view(f.name) == "plane") return f.max;
  return 0;
}
static_assert(command_plane_max() == kMaxProposalPlanes,
              "ARM_GOTO_PROPOSAL_PLANE names any plane a proposal carries");

// Whether the proposal's plane k (0-based) is offered: carried, verdict
// grindable and reach ok.
bool plane_offered(const RockProposal& p, int k);

// Index of the proposal's best offered plane (its first offered), or -1.
int offered_plane(const RockProposal& p);

// Why nothing is offered (NONE when a proposal offers a plane), from the list's counts and notes.
ProposalEmpty empty_reason(const ProposalList& list);

// The packet of a finished run (identity, region and time are the caller's):
// status 0 or 1, count, candidates, empty_reason and every slot.
tlm::Proposals proposals_packet(const ProposalList& list);

// The PROPOSAL_PLANES packet of the same run: every carried plane of every
// proposal (identity and frame are the caller's).
tlm::ProposalPlanes proposal_planes_packet(const ProposalList& list);

// SELECT_PROPOSAL's selection: the proposal's ROI, click and c as SELECT_ROI
// arguments, for SELECT_ROI's checks (cmd::selection_refusal).
cmd::SelectRoiArgs selection_args(const RockProposal& p);

}  // namespace petra::fsw
