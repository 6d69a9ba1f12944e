// EvaluationService's rock proposals: a PROPOSE run on the evaluation's
// worker, then its list to telemetry (PROPOSALS, then PROPOSAL_PLANES), the
// picture (PRODUCT kind 5) and events, and the list kept for SELECT_PROPOSAL,
// ARM_GOTO_PROPOSAL and ARM_GOTO_PROPOSAL_PLANE.
#include <algorithm>

#include "fsw/evaluation_service.hpp"
#include "fsw/proposal_packet.hpp"
#include "fsw/proposal_picture.hpp"

namespace petra::fsw {

namespace {}  // namespace

Reason EvaluationService::propose_refusal() const {
  if (!runner_.has_job()) return Reason::NO_PIPELINE;
  if (!w_.job->can_propose()) return Reason::NO_PROPOSER;
  return Reason::NONE;
}

Status EvaluationService::start_proposals(const EvalFrame& frame, const ProposalRequest& request,
                                          const ::petra::arm::JointVector& arm_pose) {
  if (propose_refusal() != Reason::NONE)
    return Error::make(Errc::not_ready, "proposals: no pipeline or no proposer");
  ++proposal_id_;  // used up even when the worker refuses: ids stay unique
  EvalRequest r = request_for(frame);
  r.kind = JobKind::PROPOSE;
  r.eval_id = proposal_id_;
  r.proposal = request;
  r.arm_pose = arm_pose;
  proposal_region_ =
      request.region.empty() ? Rect{0, 0, frame.left.width(), frame.left.height()} : request.region;
  proposal_left_ = frame.left;
  started_ns_ = w_.clock->monotonic_ns();
  PETRA_TRY(runner_.start(r));
  kind_ = JobKind::PROPOSE;
  awaiting_ = true;
  w_.events->raise(EventId::PROPOSE_STARTED, static_cast<std::int32_t>(proposal_id_),
                   static_cast<std::int32_t>(frame.sequence), request.max_proposals,
                   request.region.empty() ? 0 : 1);
  return {};
}

const RockProposal* EvaluationService::proposal(std::uint32_t proposal_id, int rank) const {
  if (listed_id_ == 0 || proposal_id != listed_id_) return nullptr;
  if (rank < 1 || rank > std::min(listed_.count, kMaxProposals)) return nullptr;
  return &listed_.items[rank - 1];
}

bool EvaluationService::publish_proposals() {
  const EvalOutput& out = runner_.output();
  const Status& s = runner_.status();
  const tlm::TmTime t = tm_time(w_.clock->realtime_ns());
  elapsed_ms_ = static_cast<std::uint32_t>(elapsed_ns() / hal::kNsPerMs);
  const bool failed = !s || out.proposals == nullptr;
  if (!failed) {
    listed_ = *out.proposals;
    listed_id_ = proposal_id_;
  }
  tlm::Proposals p = failed ? tlm::Proposals{} : proposals_packet(listed_);
  p.proposal_id = proposal_id_;
  p.frame = frame_;
  const Rect& g = proposal_region_;
  p.region_px = {static_cast<std::uint16_t>(g.x), static_cast<std::uint16_t>(g.y),
                 static_cast<std::uint16_t>(g.w), static_cast<std::uint16_t>(g.h)};
  p.total_ms = elapsed_ms_;
  const auto id = static_cast<std::int32_t>(proposal_id_);
  if (failed) {
    p.status = 2;
    p.reason = static_cast<std::uint8_t>(Reason::PIPELINE_ERROR);
    p.empty_reason = static_cast<std::uint8_t>(ProposalEmpty::FAILED);
    w_.queue->push(p, t);
    w_.events->raise(EventId::PROPOSE_FAILED, id,
                     static_cast<std::int32_t>(s ? Errc::not_ready : s.code()));
    return false;
  }
  p.picture_step = static_cast<std::uint8_t>(stage_picture(listed_));
  w_.queue->push(p, t);
  tlm::ProposalPlanes planes = proposal_planes_packet(listed_);
  planes.proposal_id = proposal_id_;
  planes.frame = frame_;
  w_.queue->push(planes, t);
  int offered = 0;
  for (int i = 0; i < p.count; ++i) offered += offered_plane(listed_.items[i]) >= 0 ? 1 : 0;
  if (p.status == 0)
    w_.events->raise(EventId::PROPOSE_COMPLETED, id, p.count, offered, p.candidates);
  else
    w_.events->raise(EventId::PROPOSE_EMPTY, id, p.empty_reason, p.count, p.candidates);
  return true;
}

// The left image at the thumbnails' decimation (at least half size a side),
// the proposals drawn; returns the step (0: refused, PRODUCT_REFUSED says why).
int EvaluationService::stage_picture(const ProposalList& list) {
  const int step =
      std::max(kProposalsPictureMinStep, w_.params->get_int(ParamId::THUMB_DECIMATION));
  const ImageView<std::uint8_t> rgb =
      w_.products->stage_gray_as_rgb(ProductKind::PROPOSALS, proposal_id_, proposal_left_, step);
  if (rgb.empty()) return 0;
  draw_proposals(rgb, step, list);
  return step;
}

}  // namespace petra::fsw
