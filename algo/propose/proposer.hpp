// Rock proposals over a whole stereo pair (issue 26; docs/proposals.md):
//   detection (algo/propose/rock_detection: the ground over the field of view,
//   the rocks standing out of it, touching rocks split at the height saddle
//   between them) -> each candidate, largest first, up to
//   budget.max_evaluated, through the chain
//   (algo/chain/pipeline: its ROI clipped to the budget's ROI, its click, c = kProposalPlanesC, DP
//   matcher) -> the run's planes that lie on this rock (their vertices' votes
//   on detection's rock map: the chain takes every rock in the ROI, so a
//   neighbour's faces are dropped here and offered by the neighbour's own run)
//   -> the rock's further flat faces from the same run (its surplus planes,
//   then algo/propose/further_planes on its mesh triangles no kept plane
//   explains, then algo/propose/flat_discs, the tool's disc over what is
//   still unexplained) in the slots the chain's accepted planes leave
//   -> each plane's approach (algo/arm plan_approach from `current`,
//   standoff arm::kDefaultStandoffMm; reachable planes first)
//   -> the score's terms and weighted total
//   -> ranking (offered proposals first, then by total) and truncation.
// c: the chain is run once per rock with c = kProposalPlanesC (3; a proposal
// carries up to kMaxProposalPlanes = 4 faces); the planes it accepts (qualified, not surplus:
// grind_planes ranks by area and keeps at most c) come first. The run's c
// counts a neighbour's planes in the ROI too, and its clustering into
// cluster_count(3) classes merges a rounded rock's smaller flat facets into a
// neighbouring class: the rock's own surplus planes (qualified past c), a
// further pass on the rest of its mesh (c = further_planes_c) and the disc
// search, which does not depend on the clustering (flat_discs), fill the
// remaining slots, one plane per face, each qualified by the chain's checks,
// its whole patch within the footprint's flatness tolerance. The operator
// sending a proposal back as SELECT_ROI with its roi, click and planes_c
// reruns exactly this chain request: the chain's accepted planes again (with
// any on a neighbour in the ROI), not the further ones (docs/proposals.md 2).
// Memory: the caller's Pipeline and its arena, shared (the flight job's one
// pipeline serves EVALUATE too): arena_bytes() = the chain's remap tables,
// then one space that detection and each chain run use in turn (the chain's
// run releases the arena to its own mark, a proposer's run to where create
// found it). The further pass takes the run's grind-plane scratch again, past
// its outputs (within the run's bytes: its grind step needed the same), and
// the disc search less than that after it. The
// proposer's own need is the detection's (detection_bytes()).
// The list and detection's rock map (12 KiB, kept through the chain runs)
// live in the Proposer. No heap after create.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "algo/arm/arm_trajectory.hpp"
#include "algo/arm/kinematics.hpp"
#include "algo/chain/pipeline.hpp"
#include "algo/core/arena.hpp"
#include "algo/core/result.hpp"
#include "algo/core/step_clock.hpp"
#include "algo/propose/arm_reach.hpp"
#include "algo/propose/flat_discs.hpp"
#include "algo/propose/further_planes.hpp"
#include "algo/propose/proposals.hpp"
#include "algo/propose/rock_detection.hpp"

namespace petra {

// c the proposer asks of the chain for every rock (see above). Asking for 4,
// the slots' count, gave the same recall and more wrong planes (docs/log.md,
// session 26).
inline constexpr int kProposalPlanesC = 3;
static_assert(kProposalPlanesC <= kMaxProposalPlanes, "the chain's accepted planes fit the slots");

struct ProposerBudget {
  PipelineBudget pipeline;  // the chain's (its max ROI is in rectified px)
  // The largest candidate ROI in original left px (SELECT_ROI's limit);
  // a larger padded rock box is cut to it around the rock's box centre.
  int max_roi_width = 512;
  int max_roi_height = 384;
  int max_evaluated = kMaxProposals;  // candidates run through the chain, largest first
  int detection_factor = 4;           // the whole pair matched at 1 / this resolution
};
Status validate(const ProposerBudget& b);

struct ProposerParams {
  DetectionParams detection;
  double standoff_mm = arm::kDefaultStandoffMm;
  // c of the further pass over a rock's faces the chain's planes leave
  // (algo/propose/further_planes; 0: off), which fills the slots after the
  // chain's accepted and surplus planes. 2 (5 classes): on the multi-rock set
  // the same recall as 3 with one wrong plane fewer; 4 and more find fewer
  // (docs/proposals.md 5).
  int further_planes_c = 2;
  // The grinder-disc search over the faces the kept planes leave
  // (algo/propose/flat_discs), after the further pass.
  bool flat_discs = true;
  FlatDiscParams discs;
};

// Field-named refusal of a request for an image of width x height.
Status validate(const ProposalRequest& r, int width, int height);

// The score's terms of a proposal's best plane (docs/proposals.md "Score").
ProposalScore score_plane(const GrindPlane* best, bool reachable, double footprint_diameter_mm,
                          const GrindParams& grind, const ProposalWeights& w);

// Per plane k of a chain run (its vertices: vertex_class kVertexPlane0 + k),
// whether it lies on another rock than `rock`: more of its vertices on
// another region standing out of the ground than on this one, in detection's
// rock map. The chain takes every rock in its ROI; the proposal keeps its own.
void planes_on_other_rocks(const ReconstructionOutput& r, const RockOnMap& rock,
                           bool (&other)[kMaxClasses]);

// A rock's grindable planes in the order they are offered, one per face
// (same_face: the chain's merge rule). A surplus plane passed every check
// (only the run's c left it out): added as accepted.
struct PlaneCandidates {
  static constexpr int kMaxCandidates = 3 * kMaxClasses;
  GrindPlane planes[kMaxCandidates];
  int count = 0;
  bool add(const GrindPlane& p, const GrindParams& grind);  // false: skipped, its face is in
  // Whether a plane's whole patch is within the footprint's tolerance (a
  // patch across a crease, two faces in one plane, is not).
  static bool flat(const GrindPlane& p, const GrindParams& grind);
  // Drops the planes from `first` on that are not flat.
  void keep_flat(int first, const GrindParams& grind);
};

class Proposer {
 public:
  Proposer() = default;

  // Arena bytes of a pipeline built for budget.pipeline and params with its
  // proposer: the tables + the larger of a chain run and detection_bytes().
  static std::size_t arena_bytes(const ProposerBudget& budget, const PipelineParams& params);
  // The detection's bytes for any envelope of budget.pipeline.max_disparities.
  static std::size_t detection_bytes(const ProposerBudget& budget);
  // `pipeline` (built for budget.pipeline, in `arena`) runs every candidate
  // with the parameters in force at the run; it must outlive the proposer.
  // The arena must hold detection_bytes() from where the tables end (its
  // mark now): create builds nothing.
  static Result<Proposer> create(Pipeline& pipeline, const ProposerBudget& budget,
                                 const arm::ArmGeometry& geometry, const arm::JointLimits& limits,
                                 Arena& arena, const ProposerParams& proposer = {});

  // Bounded; no heap. `current` = the arm's pose now (IK branch hint). The
  // list is valid until the next run; the detection's ground and counts
  // until then too (detection()).
  // `given`, when set, is a disparity map of the whole rectified left view
  // (a ground truth or another matcher's) each candidate's chain run replays
  // instead of matching (run_with_disparity): it tells the back half's share
  // of a miss from the matcher's. Detection matches as always.
  Result<const ProposalList*> run(ConstGray8View left, ConstGray8View right,
                                  const ProposalRequest& request, const arm::JointVector& current,
                                  const StepClock& clock, const ConstDisparityMap* given = nullptr);

  const DetectionResult& detection() const { return detection_; }
  const Pipeline& pipeline() const { return *pipeline_; }
  const ProposerBudget& budget() const { return budget_; }
  // The chain request a candidate is evaluated with (and SELECT_ROI repeats).
  PipelineRequest chain_request(const RockCandidate& rock) const;

 private:
  Status evaluate(ConstGray8View left, ConstGray8View right, int index,
                  const arm::JointVector& current, const ProposalWeights& weights,
                  const StepClock& clock, const ConstDisparityMap* given, RockProposal& out);
  // The candidate's chain run: matched, or `given` (whole rectified view) replayed.
  Result<PipelineOutput> run_chain(ConstGray8View left, ConstGray8View right,
                                   const PipelineRequest& q, const StepClock& clock,
                                   const ConstDisparityMap* given);
  Status own_planes(int index, const PipelineOutput& out, const ArmReach& reach,
                    RockProposal& proposal);
  void rank(const ProposalRequest& request, int evaluated);

  Pipeline* pipeline_ = nullptr;  // the caller's
  Arena* arena_ = nullptr;
  std::size_t space_mark_ = 0;  // where the tables end: detection's and the chain's space
  ProposerBudget budget_;
  ProposerParams params_;
  arm::ArmGeometry geometry_;
  arm::JointLimits limits_;
  DetectionResult detection_;
  RockMapShape rock_map_shape_;
  std::uint8_t rock_map_[kRockMapMaxWidth * kRockMapMaxHeight] = {};  // detection's rocks
  RockProposal evaluated_[kMaxProposals];
  PlaneCandidates candidates_;  // the rock's being evaluated (own_planes)
  ProposalList list_;
};

}  // namespace petra
