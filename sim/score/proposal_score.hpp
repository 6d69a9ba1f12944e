// Scores rock proposals (proposals.json) against a multi-rock scene's truth
// (truth.json "rocks"), by the rule of the proposals contract (docs/scene.md
// "Scoring proposals"): a proposal plane matches a truth facet when its normal
// is within 10 deg of the facet's and its centroid lies within 10 mm of the
// facet's plane and within 10 mm (in that plane) of the facet's polygon.
// Over the top K proposals: recall = truly grindable and reachable facets
// matched by an offered plane / all of them; precision = offered planes
// matching a grindable and reachable facet / all offered planes. Also the
// best (rank 1) proposal's first offered plane against its facet.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "sim/score/proposals_file.hpp"
#include "sim/score/truth_file.hpp"

namespace petra::sim {

inline constexpr double kProposalMatchDeg = 10.0;
inline constexpr double kProposalMatchMm = 10.0;

// Where a plane stands against one truth facet.
struct FacetMatch {
  int rock = -1;  // truth rocks[] index, -1 none
  int facet = -1;
  double normal_error_deg = 0;
  double centroid_plane_mm = 0;    // |n . (centroid - facet point)|
  double centroid_outside_mm = 0;  // in-plane distance to the polygon (0 = on it)
  bool matches = false;            // within the contract's limits
  bool target = false;             // the facet is truly grindable and reachable
};

struct ScoredPlane {
  int rank = 0;   // its proposal's
  int index = 0;  // in the proposal's planes[]
  bool offered = false;
  FacetMatch best;  // a matching facet (a target one first), else the nearest
};

struct ProposalScoreReport {
  int proposals = 0;  // in the file
  int scored = 0;     // the top K
  int offered = 0;
  int offered_on_target = 0;                // offered planes matching a grindable, reachable facet
  int targets = 0;                          // truly grindable and reachable facets
  int targets_found = 0;                    // of them, matched by an offered plane
  int facets = 0;                           // all truth facets
  std::optional<double> recall, precision;  // none when undefined (0 / 0)
  std::optional<ScoredPlane> best;          // rank 1's first offered plane
  std::vector<ScoredPlane> planes;          // every plane of the top K
  std::vector<std::pair<int, int>> missed;  // (rock, facet) targets no offered plane matched
};

// Fails when the truth has no rocks (not a multi-rock scene) or top_k < 1.
Result<ProposalScoreReport> score_proposals(const TruthFile& truth, const ProposalsFile& proposals,
                                            std::optional<int> top_k);

// Where `normal`/`centroid` stands against a facet (rock and facet indices set).
FacetMatch match_facet(const TruthFacet& facet, const Eigen::Vector3d& normal,
                       const Eigen::Vector3d& centroid);

std::string format_proposal_score_text(const ProposalScoreReport& report);
std::string format_proposal_score_json(const ProposalScoreReport& report);

}  // namespace petra::sim
