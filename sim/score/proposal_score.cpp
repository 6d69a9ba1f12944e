#include "sim/score/proposal_score.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "algo/core/json_writer.hpp"
#include "sim/score/plane_score.hpp"

namespace petra::sim {

namespace {

bool is_target(const TruthFacet& f) {
  return f.grindable && f.reachable;
}

// Order of preference: matching a target, matching, then the smallest
// mismatch (mm, plus 1 mm per degree).
bool better(const FacetMatch& a, const FacetMatch& b) {
  if (a.matches && a.target)
    return !(b.matches && b.target) || a.normal_error_deg < b.normal_error_deg;
  if (b.matches && b.target) return false;
  if (a.matches != b.matches) return a.matches;
  const double ca = a.centroid_plane_mm + a.centroid_outside_mm + a.normal_error_deg;
  const double cb = b.centroid_plane_mm + b.centroid_outside_mm + b.normal_error_deg;
  return ca < cb;
}

FacetMatch best_facet(const TruthFile& truth, const ProposalPlane& plane) {
  FacetMatch best;
  for (std::size_t r = 0; r < truth.rocks.size(); ++r)
    for (std::size_t k = 0; k < truth.rocks[r].facets.size(); ++k) {
      FacetMatch m = match_facet(truth.rocks[r].facets[k], plane.normal, plane.centroid_mm);
      m.rock = static_cast<int>(r);
      m.facet = static_cast<int>(k);
      if (best.rock < 0 || better(m, best)) best = m;
    }
  return best;
}

}  // namespace

FacetMatch match_facet(const TruthFacet& f, const Eigen::Vector3d& normal,
                       const Eigen::Vector3d& centroid) {
  FacetMatch m;
  m.normal_error_deg = angle_between_deg(normal, f.normal);
  m.centroid_plane_mm = std::abs(f.normal.dot(centroid - f.centroid_mm));
  m.centroid_outside_mm = in_plane_distance_to_polygon(f.polygon_mm, f.normal, centroid);
  m.matches = m.normal_error_deg <= kProposalMatchDeg && m.centroid_plane_mm <= kProposalMatchMm &&
              m.centroid_outside_mm <= kProposalMatchMm;
  m.target = is_target(f);
  return m;
}

Result<ProposalScoreReport> score_proposals(const TruthFile& truth, const ProposalsFile& file,
                                            std::optional<int> top_k) {
  if (truth.rocks.empty())
    return Error::make(
        Errc::missing_field,
        "truth.json: rocks: missing (a multi-rock scene: petra sim scene --rocks N)");
  if (top_k && *top_k < 1) return Error::make(Errc::out_of_range, "--top %d: must be >= 1", *top_k);
  ProposalScoreReport rep;
  rep.proposals = static_cast<int>(file.proposals.size());
  rep.scored = top_k ? std::min(*top_k, rep.proposals) : rep.proposals;
  std::vector<std::vector<bool>> found(truth.rocks.size());
  for (std::size_t r = 0; r < truth.rocks.size(); ++r) {
    found[r].assign(truth.rocks[r].facets.size(), false);
    for (const auto& f : truth.rocks[r].facets) {
      ++rep.facets;
      rep.targets += is_target(f) ? 1 : 0;
    }
  }
  for (int p = 0; p < rep.scored; ++p) {
    const Proposal& prop = file.proposals[static_cast<std::size_t>(p)];
    for (std::size_t k = 0; k < prop.planes.size(); ++k) {
      ScoredPlane sp{prop.rank, static_cast<int>(k), prop.planes[k].offered(),
                     best_facet(truth, prop.planes[k])};
      if (sp.offered) {
        ++rep.offered;
        // Every target facet this plane matches counts as found.
        for (std::size_t r = 0; r < truth.rocks.size(); ++r)
          for (std::size_t f = 0; f < truth.rocks[r].facets.size(); ++f) {
            const FacetMatch m = match_facet(truth.rocks[r].facets[f], prop.planes[k].normal,
                                             prop.planes[k].centroid_mm);
            if (m.matches && m.target) found[r][f] = true;
          }
        rep.offered_on_target += sp.best.matches && sp.best.target ? 1 : 0;
        if (!rep.best && p == 0) rep.best = sp;
      }
      rep.planes.push_back(sp);
    }
  }
  for (std::size_t r = 0; r < truth.rocks.size(); ++r)
    for (std::size_t f = 0; f < found[r].size(); ++f) {
      if (!is_target(truth.rocks[r].facets[f])) continue;
      if (found[r][f])
        ++rep.targets_found;
      else
        rep.missed.emplace_back(static_cast<int>(r), static_cast<int>(f));
    }
  if (rep.targets > 0) rep.recall = double(rep.targets_found) / rep.targets;
  if (rep.offered > 0) rep.precision = double(rep.offered_on_target) / rep.offered;
  return rep;
}

namespace {

std::string figure(const std::optional<double>& v) {
  if (!v) return "n/a";
  char b[32];
  std::snprintf(b, sizeof b, "%.3f", *v);
  return b;
}

std::string plane_line(const ScoredPlane& p) {
  char b[256];
  const FacetMatch& m = p.best;
  std::snprintf(b, sizeof b,
                "  rank %d plane %d%s: %s rock %d facet %d (%s), normal %.2f deg, "
                "centroid-plane %.2f mm, outside %.2f mm\n",
                p.rank, p.index, p.offered ? " offered" : "", m.matches ? "matches" : "nearest",
                m.rock, m.facet, m.target ? "grindable, reachable" : "not a target",
                m.normal_error_deg, m.centroid_plane_mm, m.centroid_outside_mm);
  return b;
}

}  // namespace

std::string format_proposal_score_text(const ProposalScoreReport& r) {
  std::string out;
  char b[256];
  std::snprintf(b, sizeof b, "proposals: %d scored of %d, %d offered planes\n", r.scored,
                r.proposals, r.offered);
  out += b;
  std::snprintf(b, sizeof b, "truth: %d grindable and reachable facets of %d\n", r.targets,
                r.facets);
  out += b;
  std::snprintf(b, sizeof b, "recall:    %s (%d of %d)\nprecision: %s (%d of %d)\n",
                figure(r.recall).c_str(), r.targets_found, r.targets, figure(r.precision).c_str(),
                r.offered_on_target, r.offered);
  out += b;
  if (r.best) {
    const FacetMatch& m = r.best->best;
    std::snprintf(b, sizeof b,
                  "best (rank 1, plane %d): rock %d facet %d%s: normal %.2f deg, centroid-plane "
                  "%.2f mm, on facet %s\n",
                  r.best->index, m.rock, m.facet, m.matches ? "" : " (nearest, no match)",
                  m.normal_error_deg, m.centroid_plane_mm,
                  m.centroid_outside_mm == 0 ? "yes" : "no");
    out += b;
  } else {
    out += "best: rank 1 offers no plane\n";
  }
  for (const auto& p : r.planes) out += plane_line(p);
  for (const auto& [rock, facet] : r.missed) {
    std::snprintf(b, sizeof b, "  missed: rock %d facet %d\n", rock, facet);
    out += b;
  }
  return out;
}

namespace {

void write_optional(json::Writer& w, const char* key, const std::optional<double>& v) {
  w.key(key);
  if (v)
    w.number(*v);
  else
    w.number(std::nan(""));  // written as null
}

void write_plane(json::Writer& w, const ScoredPlane& p) {
  const FacetMatch& m = p.best;
  w.begin_object();
  w.key("rank").integer(p.rank);
  w.key("plane").integer(p.index);
  w.key("offered").boolean(p.offered);
  w.key("matches").boolean(m.matches);
  w.key("rock").integer(m.rock);
  w.key("facet").integer(m.facet);
  w.key("target").boolean(m.target);
  w.key("normal_error_deg").number(m.normal_error_deg);
  w.key("centroid_plane_mm").number(m.centroid_plane_mm);
  w.key("centroid_outside_mm").number(m.centroid_outside_mm);
  w.key("on_facet").boolean(m.centroid_outside_mm == 0);
  w.end_object();
}

}  // namespace

std::string format_proposal_score_json(const ProposalScoreReport& r) {
  std::vector<char> buf(std::size_t{1} << 20);
  json::Writer w({buf.data(), buf.size()});
  w.begin_object();
  w.key("proposals").integer(r.proposals);
  w.key("scored").integer(r.scored);
  w.key("offered").integer(r.offered);
  w.key("offered_on_target").integer(r.offered_on_target);
  w.key("targets").integer(r.targets);
  w.key("targets_found").integer(r.targets_found);
  w.key("facets").integer(r.facets);
  write_optional(w, "recall", r.recall);
  write_optional(w, "precision", r.precision);
  w.key("best");
  if (r.best)
    write_plane(w, *r.best);
  else
    w.number(std::nan(""));  // written as null
  w.key("planes").begin_array();
  for (const auto& p : r.planes) write_plane(w, p);
  w.end_array();
  w.key("missed").begin_array();
  for (const auto& [rock, facet] : r.missed)
    w.begin_array().integer(rock).integer(facet).end_array();
  w.end_array();
  w.end_object();
  w.raw("\n");
  auto n = w.finish();
  return n ? std::string(buf.data(), *n) : std::string("{}\n");
}

}  // namespace petra::sim
