#include "fsw/proposal_packet.hpp"

#include <algorithm>

namespace petra::fsw {

namespace {

std::uint16_t px(int v, int max = 8192) {
  return static_cast<std::uint16_t>(std::clamp(v, 0, max));
}

float unit(double v) {
  return static_cast<float>(std::clamp(v, 0.0, 1.0));
}

// Plane k of p into plane slot i of the arrays of a packet (PROPOSALS shows
// one plane per proposal, PROPOSAL_PLANES every one: the same fields).
template <class Packet>
void put_plane_fields(const RockProposal& p, int k, std::size_t i, Packet& t) {
  const GrindPlane& g = p.planes[k];
  for (std::size_t c = 0; c < 3; ++c) {
    t.normal[3 * i + c] = static_cast<float>(g.normal[static_cast<int>(c)]);
    t.centroid_mm[3 * i + c] = static_cast<float>(g.centroid_mm[static_cast<int>(c)]);
  }
  t.area_mm2[i] = static_cast<float>(g.area_mm2);
  t.normal_sigma_deg[i] = static_cast<float>(g.normal_sigma_deg);
  t.offset_sigma_mm[i] = static_cast<float>(g.offset_sigma_mm);
  t.verdict[i] = static_cast<std::uint8_t>(g.verdict);
  t.reach[i] = static_cast<std::uint8_t>(p.reach[k]);
}

std::uint8_t carried(const RockProposal& p) {
  return static_cast<std::uint8_t>(std::clamp(p.plane_count, 0, kMaxProposalPlanes));
}

// The plane shown: the best offered one, else the first (its verdict and reach say why).
void put_plane(const RockProposal& p, std::size_t i, tlm::Proposals& t) {
  t.plane_count[i] = carried(p);
  if (p.plane_count <= 0) return;
  const int offered = offered_plane(p);
  t.plane_offered[i] = offered >= 0 ? 1 : 0;
  put_plane_fields(p, offered >= 0 ? offered : 0, i, t);
}

void put_slot(const RockProposal& p, std::size_t i, tlm::Proposals& t) {
  t.rank[i] = static_cast<std::uint8_t>(i + 1);
  const Rect& r = p.rock.roi;
  t.roi_px[4 * i + 0] = px(r.x);
  t.roi_px[4 * i + 1] = px(r.y);
  t.roi_px[4 * i + 2] = px(r.w);
  t.roi_px[4 * i + 3] = px(r.h);
  t.click_px[2 * i + 0] = px(p.rock.click_u, 8191);
  t.click_px[2 * i + 1] = px(p.rock.click_v, 8191);
  t.height_mm[i] = static_cast<float>(std::max(p.rock.height_mm, 0.0));
  t.size_mm[i] = static_cast<float>(std::max(p.rock.size_mm, 0.0));
  t.planes_c[i] = static_cast<std::uint8_t>(std::clamp(p.planes_c, 0, 8));
  t.note[i] = static_cast<std::uint8_t>(p.note);
  t.score_total[i] = unit(p.score.total);
  t.score_grindable[i] = unit(p.score.grindable);
  t.score_reach[i] = unit(p.score.reach);
  t.score_certainty[i] = unit(p.score.certainty);
  t.score_size[i] = unit(p.score.size);
  put_plane(p, i, t);
}

}  // namespace

bool plane_offered(const RockProposal& p, int k) {
  return k >= 0 && k < std::min(p.plane_count, kMaxProposalPlanes) &&
         p.planes[k].verdict == PlaneVerdict::accepted && p.reach[k] == ::petra::arm::ArmReason::ok;
}

int offered_plane(const RockProposal& p) {
  for (int k = 0; k < kMaxProposalPlanes; ++k)
    if (plane_offered(p, k)) return k;
  return -1;
}

ProposalEmpty empty_reason(const ProposalList& list) {
  const int n = std::clamp(list.count, 0, kMaxProposals);
  if (n == 0) return list.candidates == 0 ? ProposalEmpty::NO_ROCK : ProposalEmpty::NONE_KEPT;
  bool grindable = false;
  for (int i = 0; i < n; ++i) {
    const RockProposal& p = list.items[i];
    if (offered_plane(p) >= 0) return ProposalEmpty::NONE;
    for (int k = 0; k < std::min(p.plane_count, kMaxProposalPlanes); ++k)
      grindable = grindable || p.planes[k].verdict == PlaneVerdict::accepted;
  }
  return grindable ? ProposalEmpty::NONE_REACHABLE : ProposalEmpty::NONE_GRINDABLE;
}

tlm::Proposals proposals_packet(const ProposalList& list) {
  tlm::Proposals t;
  const int n = std::clamp(list.count, 0, kMaxProposals);
  t.count = static_cast<std::uint8_t>(n);
  t.candidates = static_cast<std::uint16_t>(std::clamp(list.candidates, 0, 65535));
  const ProposalEmpty why = empty_reason(list);
  t.empty_reason = static_cast<std::uint8_t>(why);
  t.status = why == ProposalEmpty::NONE ? 0 : 1;
  for (int i = 0; i < n; ++i) put_slot(list.items[i], static_cast<std::size_t>(i), t);
  return t;
}

tlm::ProposalPlanes proposal_planes_packet(const ProposalList& list) {
  tlm::ProposalPlanes t;
  const int n = std::clamp(list.count, 0, kMaxProposals);
  t.count = static_cast<std::uint8_t>(n);
  for (int i = 0; i < n; ++i) {
    const RockProposal& p = list.items[i];
    t.plane_count[static_cast<std::size_t>(i)] = carried(p);
    for (int k = 0; k < carried(p); ++k) {
      const auto slot = static_cast<std::size_t>(i * kMaxProposalPlanes + k);
      t.offered[slot] = plane_offered(p, k) ? 1 : 0;
      put_plane_fields(p, k, slot, t);
    }
  }
  return t;
}

cmd::SelectRoiArgs selection_args(const RockProposal& p) {
  cmd::SelectRoiArgs a;
  const Rect& r = p.rock.roi;
  a.x_px = px(r.x);
  a.y_px = px(r.y);
  a.w_px = px(r.w);
  a.h_px = px(r.h);
  a.planes = static_cast<std::uint8_t>(std::clamp(p.planes_c, 0, 255));
  a.has_click = 1;
  a.click_u_px = px(p.rock.click_u, 8191);
  a.click_v_px = px(p.rock.click_v, 8191);
  return a;
}

}  // namespace petra::fsw
