// proposals.json (`petra propose`, docs/proposals.md; the shape is the
// contract of issue 26, read by `petra score proposals` and the ground
// station): the ranked proposals, each with its ROI, click, height, size, the
// c it was evaluated with, its note and a one-line reason, the score and its
// terms, and its planes (verdict, reach, 1-sigma); the number of rocks
// detected and why nothing is offered when nothing is.
#pragma once

#include <string>

#include "algo/propose/proposals.hpp"

namespace petra::eval {

std::string format_proposals_json(const ProposalList& list);

// The one-line reason of a proposal's note (proposals.json "reason").
std::string proposal_reason(const RockProposal& p);

}  // namespace petra::eval
