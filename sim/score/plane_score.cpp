#include "sim/score/plane_score.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

namespace petra::sim {

namespace {

// The normals' angle counts without their sign: a flipped plane is matched to
// the facet it lies on (and reads 180 deg there), not to another facet.
double match_cost(const TruthFacet& f, const OutputPlane& p) {
  const double a = angle_between_deg(f.normal, p.normal);
  return distance_to_polygon(f.polygon_mm, f.normal, p.centroid_mm) +
         kMatchMmPerDeg * std::min(a, 180.0 - a);
}

// Optimal one-to-one assignment by dynamic programming over the subsets of
// facets (at most 16), taking the planes one at a time in rank order.
std::vector<int> assign(const std::vector<std::vector<double>>& cost, int n_facets, int n_planes) {
  const std::size_t masks = std::size_t{1} << n_facets;
  constexpr double kInf = std::numeric_limits<double>::infinity();
  // best[j][mask]: least cost using planes < j to match exactly the facets in mask.
  std::vector<std::vector<double>> best(static_cast<std::size_t>(n_planes) + 1,
                                        std::vector<double>(masks, kInf));
  std::vector<std::vector<int>> choice(static_cast<std::size_t>(n_planes) + 1,
                                       std::vector<int>(masks, -1));
  best[0][0] = 0;
  for (int j = 0; j < n_planes; ++j) {
    const auto& cur = best[static_cast<std::size_t>(j)];
    auto& next = best[static_cast<std::size_t>(j) + 1];
    auto& pick = choice[static_cast<std::size_t>(j) + 1];
    for (std::size_t m = 0; m < masks; ++m) {
      if (cur[m] == kInf) continue;
      if (cur[m] < next[m]) {  // plane j unmatched
        next[m] = cur[m];
        pick[m] = -1;
      }
      for (int i = 0; i < n_facets; ++i) {
        const std::size_t bit = std::size_t{1} << i;
        if (m & bit) continue;
        const double c = cur[m] + cost[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)];
        if (c < next[m | bit]) {
          next[m | bit] = c;
          pick[m | bit] = i;
        }
      }
    }
  }
  // As many matches as possible, then the least cost.
  const auto& last = best[static_cast<std::size_t>(n_planes)];
  std::size_t best_mask = 0;
  for (std::size_t m = 1; m < masks; ++m) {
    if (last[m] == kInf) continue;
    const int pm = std::popcount(m), pb = std::popcount(best_mask);
    if (pm > pb || (pm == pb && last[m] < last[best_mask])) best_mask = m;
  }
  std::vector<int> plane_of(static_cast<std::size_t>(n_facets), -1);
  std::size_t m = best_mask;
  for (int j = n_planes; j > 0; --j) {
    const int i = choice[static_cast<std::size_t>(j)][m];
    if (i >= 0) {
      plane_of[static_cast<std::size_t>(i)] = j - 1;
      m &= ~(std::size_t{1} << i);
    }
  }
  return plane_of;
}

}  // namespace

PlaneScore score_planes(const TruthFile& truth, const PlanesFile& out) {
  PlaneScore s;
  s.truth_planes = truth.planes;
  s.output_planes = static_cast<int>(out.planes.size());
  s.count_agrees = s.truth_planes == s.output_planes;
  const int nf = std::min(static_cast<int>(truth.facets.size()), 16);
  const int designed = std::min(truth.planes, nf);
  const int np = s.output_planes;
  std::vector<std::vector<double>> cost(static_cast<std::size_t>(nf),
                                        std::vector<double>(static_cast<std::size_t>(np)));
  for (int i = 0; i < nf; ++i)
    for (int j = 0; j < np; ++j)
      cost[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)] = match_cost(
          truth.facets[static_cast<std::size_t>(i)], out.planes[static_cast<std::size_t>(j)]);
  const std::vector<int> plane_of = assign(cost, nf, np);
  std::vector<bool> used(static_cast<std::size_t>(np), false);
  for (int i = 0; i < nf; ++i) {
    const TruthFacet& f = truth.facets[static_cast<std::size_t>(i)];
    FacetScore fs;
    fs.facet = i;
    fs.plane = plane_of[static_cast<std::size_t>(i)];
    if (i >= designed && fs.plane < 0) continue;
    if (fs.plane >= 0) {
      const OutputPlane& p = out.planes[static_cast<std::size_t>(fs.plane)];
      used[static_cast<std::size_t>(fs.plane)] = true;
      fs.normal_error_deg = angle_between_deg(f.normal, p.normal);
      fs.centroid_plane_distance_mm = std::abs(f.normal.dot(p.centroid_mm - f.polygon_mm[0]));
      fs.centroid_outside_mm = in_plane_distance_to_polygon(f.polygon_mm, f.normal, p.centroid_mm);
      fs.centroid_on_facet = fs.centroid_outside_mm == 0.0;
    }
    (i < designed ? s.facets : s.other_facets).push_back(fs);
  }
  for (int j = 0; j < np; ++j)
    if (!used[static_cast<std::size_t>(j)]) s.extra_planes.push_back(j);

  if (out.ground) {
    GroundScore g;
    const Eigen::Vector3d& nt = truth.ground_normal;
    const Eigen::Vector3d& no = out.ground->normal;
    g.normal_error_deg = angle_between_deg(nt, no.dot(nt) < 0 ? Eigen::Vector3d(-no) : no);
    // Where the ground is under the rock: the scored facets' mean centroid,
    // dropped onto the truth ground plane.
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (int i = 0; i < designed; ++i) c += truth.facets[static_cast<std::size_t>(i)].centroid_mm;
    if (designed > 0) c /= designed;
    const Eigen::Vector3d q = c - nt * (nt.dot(c) + truth.ground_d_mm);
    g.height_error_mm = std::abs(no.dot(q) + out.ground->d_mm);
    s.ground = g;
  }
  return s;
}

double angle_between_deg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0)) * 180.0 / M_PI;
}

}  // namespace petra::sim
