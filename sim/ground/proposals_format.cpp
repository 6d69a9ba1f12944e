#include "sim/ground/proposals_format.hpp"

#include <cctype>
#include <cstdio>

#include "algo/arm/kinematics.hpp"
#include "algo/propose/proposals.hpp"
#include "algo/surface/grind_planes.hpp"
#include "algo/wire/reasons.hpp"

namespace petra::ground {

std::string proposal_empty_name(long code) {
  const char* name = nullptr;
  switch (code) {
#define PETRA_EMPTY_NAME(NAME, c, desc) \
  case c:                               \
    name = #NAME;                       \
    break;
    PETRA_PROPOSAL_EMPTY_REASONS(PETRA_EMPTY_NAME)
#undef PETRA_EMPTY_NAME
  }
  if (name == nullptr) return "empty reason " + std::to_string(code);
  std::string s = name;
  for (char& ch : s) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  return s;
}

const char* proposal_note_key(std::uint8_t note) {
  return proposal_note_name(static_cast<ProposalNote>(note));
}

namespace {

// Plane slot k of either packet (PROPOSALS' plane shown, PROPOSAL_PLANES'
// carried planes: the same fields): normal, centroid, area, sigma, verdict, reach.
template <class Packet>
std::string plane_text(const Packet& p, std::size_t k) {
  char buf[320];
  const int n = std::snprintf(
      buf, sizeof(buf),
      "normal (%.4f, %.4f, %.4f) centroid (%.2f, %.2f, %.2f) mm area %.0f mm2 "
      "sigma %.2f deg %.2f mm, %s, reach %s",
      static_cast<double>(p.normal[3 * k]), static_cast<double>(p.normal[3 * k + 1]),
      static_cast<double>(p.normal[3 * k + 2]), static_cast<double>(p.centroid_mm[3 * k]),
      static_cast<double>(p.centroid_mm[3 * k + 1]), static_cast<double>(p.centroid_mm[3 * k + 2]),
      static_cast<double>(p.area_mm2[k]), static_cast<double>(p.normal_sigma_deg[k]),
      static_cast<double>(p.offset_sigma_mm[k]),
      verdict_key(static_cast<PlaneVerdict>(p.verdict[k])),
      arm::arm_reason_name(static_cast<arm::ArmReason>(p.reach[k])));
  return std::string(buf, static_cast<std::size_t>(n < 0 ? 0 : std::min<int>(n, sizeof(buf) - 1)));
}

std::string slot_line(const tlm::Proposals& p, std::size_t i) {
  char buf[512];
  const int n = std::snprintf(
      buf, sizeof(buf),
      "  #%u roi (%u, %u, %u x %u) click (%u, %u) rock %.1f mm high %.1f mm wide, c = %u, %s; "
      "score %.3f (grindable %.2f reach %.2f certainty %.2f size %.2f)",
      p.rank[i], p.roi_px[4 * i], p.roi_px[4 * i + 1], p.roi_px[4 * i + 2], p.roi_px[4 * i + 3],
      p.click_px[2 * i], p.click_px[2 * i + 1], static_cast<double>(p.height_mm[i]),
      static_cast<double>(p.size_mm[i]), p.planes_c[i], proposal_note_key(p.note[i]),
      static_cast<double>(p.score_total[i]), static_cast<double>(p.score_grindable[i]),
      static_cast<double>(p.score_reach[i]), static_cast<double>(p.score_certainty[i]),
      static_cast<double>(p.score_size[i]));
  std::string out(buf, static_cast<std::size_t>(n < 0 ? 0 : std::min<int>(n, sizeof(buf) - 1)));
  if (p.plane_count[i] == 0) return out + "; no plane";
  return out + "; " + (p.plane_offered[i] != 0 ? "offered" : "best (not offered)") + " plane " +
         plane_text(p, i) + " (" + std::to_string(p.plane_count[i]) + " planes)";
}

// Plane slot k of PROPOSAL_PLANES: rank k / P + 1, plane k % P + 1
// (P = PETRA_MAX_PROPOSAL_PLANES).
std::string plane_line(const tlm::ProposalPlanes& p, std::size_t k) {
  return "  #" + std::to_string(k / PETRA_MAX_PROPOSAL_PLANES + 1) + "." +
         std::to_string(k % PETRA_MAX_PROPOSAL_PLANES + 1) + " " +
         (p.offered[k] != 0 ? "offered" : "not offered") + ": " + plane_text(p, k);
}

}  // namespace

std::string format_proposal_planes(const tlm::ProposalPlanes& p) {
  const std::size_t n = p.count < PETRA_MAX_PROPOSALS ? p.count : PETRA_MAX_PROPOSALS;
  std::size_t planes = 0, offered = 0;
  std::string lines;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < p.plane_count[i] && j < PETRA_MAX_PROPOSAL_PLANES; ++j) {
      const std::size_t k = i * PETRA_MAX_PROPOSAL_PLANES + j;
      ++planes;
      offered += p.offered[k] != 0 ? 1 : 0;
      lines += '\n';  // appended apart: "\n" + string trips GCC 12's -Wrestrict (a false report)
      lines += plane_line(p, k);
    }
  return "proposal planes " + std::to_string(p.proposal_id) + " on pair " +
         std::to_string(p.frame) + ": " + std::to_string(planes) + " planes of " +
         std::to_string(n) + " proposals, " + std::to_string(offered) + " offered" + lines;
}

std::string format_proposals(const tlm::Proposals& p) {
  char buf[256];
  std::snprintf(buf, sizeof(buf),
                "proposals %u on pair %u: %u listed of %u rocks detected in (%u, %u, %u x %u) in "
                "%u ms",
                p.proposal_id, p.frame, p.count, p.candidates, p.region_px[0], p.region_px[1],
                p.region_px[2], p.region_px[3], p.total_ms);
  std::string out = buf;
  if (p.status == 2) return out + "; FAILED: " + reason_name(static_cast<Reason>(p.reason));
  if (p.status == 1) out += "; nothing offered: " + proposal_empty_name(p.empty_reason);
  const std::size_t n = p.count < PETRA_MAX_PROPOSALS ? p.count : PETRA_MAX_PROPOSALS;
  for (std::size_t i = 0; i < n; ++i) {
    out += '\n';  // appended apart: "\n" + string trips GCC 12's -Wrestrict (a false report)
    out += slot_line(p, i);
  }
  return out;
}

}  // namespace petra::ground
