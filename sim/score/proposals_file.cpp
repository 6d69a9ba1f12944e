#include "sim/score/proposals_file.hpp"

#include <algorithm>
#include <string>

#include "sim/score/json_fields.hpp"

namespace petra::sim {

namespace {

Result<ProposalPlane> read_plane(const JsonFile& f, std::uint32_t i, const std::string& p) {
  PETRA_TRY(f.object(i, p));
  ProposalPlane plane;
  auto n = f.member(i, "normal", p + ".normal");
  if (!n) return n.error();
  auto nv = f.unit_vec3(*n, p + ".normal");
  if (!nv) return nv.error();
  plane.normal = *nv;
  auto c = f.member(i, "centroid_mm", p + ".centroid_mm");
  if (!c) return c.error();
  auto cv = f.vec3(*c, p + ".centroid_mm");
  if (!cv) return cv.error();
  plane.centroid_mm = *cv;
  auto verdict = f.member(i, "verdict", p + ".verdict");
  if (!verdict) return verdict.error();
  auto vv = f.string(*verdict, p + ".verdict");
  if (!vv) return vv.error();
  plane.verdict = *vv;
  auto reach = f.member(i, "reach", p + ".reach");
  if (!reach) return reach.error();
  auto rv = f.string(*reach, p + ".reach");
  if (!rv) return rv.error();
  plane.reach = *rv;
  if (const std::uint32_t a = f.optional_member(i, "area_mm2")) {
    auto av = f.number(a, p + ".area_mm2");
    if (!av) return av.error();
    plane.area_mm2 = *av;
  }
  return plane;
}

Result<Proposal> read_proposal(const JsonFile& f, std::uint32_t i, const std::string& p) {
  PETRA_TRY(f.object(i, p));
  Proposal out;
  auto rank = f.member(i, "rank", p + ".rank");
  if (!rank) return rank.error();
  auto rv = f.integer(*rank, p + ".rank");
  if (!rv) return rv.error();
  if (*rv < 1) return f.error(p + ".rank", "must be >= 1");
  out.rank = static_cast<int>(*rv);
  if (const std::uint32_t note = f.optional_member(i, "note")) {
    auto nv = f.string(note, p + ".note");
    if (!nv) return nv.error();
    out.note = *nv;
  }
  auto planes = f.member(i, "planes", p + ".planes");
  if (!planes) return planes.error();
  PETRA_TRY(f.array(*planes, p + ".planes"));
  const auto list = f.elements(*planes);
  for (std::size_t k = 0; k < list.size(); ++k) {
    auto plane = read_plane(f, list[k], p + ".planes[" + std::to_string(k) + "]");
    if (!plane) return plane.error();
    out.planes.push_back(std::move(*plane));
  }
  return out;
}

}  // namespace

Result<ProposalsFile> parse_proposals_json(std::string_view text, const char* name) {
  auto parsed = JsonFile::parse(std::string(text), name);
  if (!parsed) return parsed.error();
  const JsonFile& f = *parsed;
  ProposalsFile out;
  auto list = f.member(0, "proposals", "proposals");
  if (!list) return list.error();
  PETRA_TRY(f.array(*list, "proposals"));
  const auto items = f.elements(*list);
  for (std::size_t k = 0; k < items.size(); ++k) {
    auto p = read_proposal(f, items[k], "proposals[" + std::to_string(k) + "]");
    if (!p) return p.error();
    out.proposals.push_back(std::move(*p));
  }
  if (const std::uint32_t c = f.optional_member(0, "candidates")) {
    auto cv = f.integer(c, "candidates");
    if (!cv) return cv.error();
    out.candidates = *cv;
  }
  if (const std::uint32_t e = f.optional_member(0, "empty_reason")) {
    auto ev = f.string(e, "empty_reason");
    if (!ev) return ev.error();
    out.empty_reason = *ev;
  }
  std::stable_sort(out.proposals.begin(), out.proposals.end(),
                   [](const Proposal& a, const Proposal& b) { return a.rank < b.rank; });
  return out;
}

}  // namespace petra::sim
