#include "sim/eval/proposals_json.hpp"

#include <cstdio>
#include <vector>

#include "algo/core/json_writer.hpp"
#include "sim/io/json_vec3.hpp"

namespace petra::eval {

namespace {

void plane(json::Writer& w, const GrindPlane& p, arm::ArmReason reach) {
  w.begin_object();
  w.key("normal");
  sim::write_vec3(w, p.normal);
  // As planes.json: centroid_mm is the face's area centroid.
  w.key("centroid_mm");
  sim::write_vec3(w, p.face_centroid_mm);
  // Where ARM_GOTO_PROPOSAL_PLANE takes the grinder, and why there.
  w.key("grind_point_mm");
  sim::write_vec3(w, p.centroid_mm);
  if (p.footprint_reach != FootprintReach::not_asked)
    w.key("footprint_reach").string(footprint_reach_key(p.footprint_reach));
  w.key("area_mm2").number(p.area_mm2);
  w.key("rms_mm").number(p.rms_mm);
  w.key("verdict").string(verdict_key(p.verdict));
  w.key("reach").string(arm::arm_reason_name(reach));
  w.key("normal_sigma_deg").number(p.normal_sigma_deg);
  w.key("offset_sigma_mm").number(p.offset_sigma_mm);
  w.end_object();
}

void proposal(json::Writer& w, const RockProposal& p, int rank) {
  const RockCandidate& r = p.rock;
  w.begin_object();
  w.key("rank").integer(rank);
  w.key("roi").begin_array().integer(r.roi.x).integer(r.roi.y).integer(r.roi.w).integer(r.roi.h);
  w.end_array();
  w.key("click").begin_array().integer(r.click_u).integer(r.click_v).end_array();
  w.key("height_mm").number(r.height_mm);
  w.key("size_mm").number(r.size_mm);
  w.key("planes_c").integer(p.planes_c);
  w.key("note").string(proposal_note_name(p.note));
  w.key("reason").string(proposal_reason(p));
  w.key("score").begin_object();
  w.key("total").number(p.score.total);
  w.key("grindable").number(p.score.grindable);
  w.key("reach").number(p.score.reach);
  w.key("certainty").number(p.score.certainty);
  w.key("size").number(p.score.size);
  w.end_object();
  w.key("planes").begin_array();
  for (int k = 0; k < p.plane_count; ++k) plane(w, p.planes[k], p.reach[k]);
  w.end_array();
  w.end_object();
}

}  // namespace

std::string proposal_reason(const RockProposal& p) {
  char line[320];
  int accepted = 0, offered = -1;
  for (int k = 0; k < p.plane_count; ++k)
    if (p.planes[k].verdict == PlaneVerdict::accepted) {
      ++accepted;
      if (offered < 0 && p.reach[k] == arm::ArmReason::ok) offered = k;
    }
  switch (p.note) {
    case ProposalNote::ok:
      std::snprintf(line, sizeof line,
                    "plane %d grindable and reachable; %d of c = %d planes accepted", offered + 1,
                    accepted, p.planes_c);
      break;
    case ProposalNote::chain_refused:
      std::snprintf(line, sizeof line, "chain refused: %s", p.chain_error.message);
      break;
    case ProposalNote::unreachable:
      std::snprintf(line, sizeof line, "%d grindable planes, none reachable (plane 1: %s)",
                    accepted, arm::arm_reason_name(p.reach[0]));
      break;
    case ProposalNote::no_grindable_plane:
      if (p.plane_count > 0)
        std::snprintf(line, sizeof line, "no plane qualified (plane 1: %s)",
                      verdict_name(p.planes[0].verdict));
      else
        std::snprintf(line, sizeof line, "no plane found on the rock");
      break;
  }
  return line;
}

std::string format_proposals_json(const ProposalList& list) {
  std::vector<char> buf(2048 + 4096 * static_cast<std::size_t>(list.count));
  json::Writer w(buf);
  w.begin_object();
  w.key("proposals").begin_array();
  for (int i = 0; i < list.count; ++i) {
    w.raw("\n ");
    proposal(w, list.items[i], i + 1);
  }
  w.end_array();
  w.raw("\n");
  w.key("candidates").integer(list.candidates);
  w.key("empty_reason").string(list.empty_reason);
  w.end_object();
  w.raw("\n");
  auto n = w.finish();
  return n ? std::string(w.view()) : std::string();
}

}  // namespace petra::eval
