#include "algo/grind_planes.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "algo/plane_fit.hpp"

namespace petra {

namespace {

constexpr std::uint8_t kNone = 0xFF;

template <class T>
std::size_t bytes_for(std::size_t n) {
  return n * sizeof(T) + alignof(T);
}

struct Scratch {
  std::span<Eigen::Vector3d> normal, centroid, sample;
  std::span<std::uint8_t> sample_cls;
  std::span<double> area;
  std::span<std::uint8_t> cls, support, depth;
  std::span<std::int32_t> queue;
};

Result<Scratch> allocate(Arena& arena, std::size_t n) {
  Scratch s;
  auto normal = arena.allocate<Eigen::Vector3d>(n, "grind planes normals");
  if (!normal) return normal.error();
  auto centroid = arena.allocate<Eigen::Vector3d>(n, "grind planes centroids");
  if (!centroid) return centroid.error();
  auto area = arena.allocate<double>(n, "grind planes areas");
  if (!area) return area.error();
  auto cls = arena.allocate<std::uint8_t>(n, "grind planes classes");
  if (!cls) return cls.error();
  auto support = arena.allocate<std::uint8_t>(n, "grind planes support");
  if (!support) return support.error();
  auto depth = arena.allocate<std::uint8_t>(n, "grind planes border depth");
  if (!depth) return depth.error();
  s.depth = *depth;
  auto queue = arena.allocate<std::int32_t>(n, "grind planes queue");
  if (!queue) return queue.error();
  auto sample = arena.allocate<Eigen::Vector3d>(kCMeansSamples, "c-means samples");
  if (!sample) return sample.error();
  auto sample_cls = arena.allocate<std::uint8_t>(kCMeansSamples, "c-means sample classes");
  if (!sample_cls) return sample_cls.error();
  s.sample = *sample;
  s.sample_cls = *sample_cls;
  s.normal = *normal;
  s.centroid = *centroid;
  s.area = *area;
  s.cls = *cls;
  s.support = *support;
  s.queue = *queue;
  return s;
}

double angle_deg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b)) * 180.0 / M_PI;
}

// Marks (support[i] = 1) the largest edge-connected patch of class k, by area.
// Breadth-first with an explicit queue; `support` doubles as the visited mark
// (2 = visited, not chosen).
void largest_patch(std::span<const MeshTriangle> tris, const Scratch& s, std::uint8_t k) {
  const std::size_t n = tris.size();
  std::size_t best_start = n;
  double best_area = -1;
  for (std::size_t i = 0; i < n; ++i) s.support[i] = 0;
  for (std::size_t seed = 0; seed < n; ++seed) {
    if (s.cls[seed] != k || s.support[seed] != 0) continue;
    std::size_t head = 0, tail = 0;
    double area = 0;
    s.queue[tail++] = static_cast<std::int32_t>(seed);
    s.support[seed] = 2;
    while (head < tail) {
      const std::size_t t = static_cast<std::size_t>(s.queue[head++]);
      area += s.area[t];
      for (int e = 0; e < 3; ++e) {
        const std::int32_t nb = tris[t].n[e];
        if (nb < 0) continue;
        const std::size_t u = static_cast<std::size_t>(nb);
        if (s.cls[u] != k || s.support[u] != 0) continue;
        s.support[u] = 2;
        s.queue[tail++] = nb;
      }
    }
    if (area > best_area) {
      best_area = area;
      best_start = seed;
    }
  }
  for (std::size_t i = 0; i < n; ++i) s.support[i] = 0;
  if (best_start == n) return;
  std::size_t head = 0, tail = 0;
  s.queue[tail++] = static_cast<std::int32_t>(best_start);
  s.support[best_start] = 1;
  while (head < tail) {
    const std::size_t t = static_cast<std::size_t>(s.queue[head++]);
    for (int e = 0; e < 3; ++e) {
      const std::int32_t nb = tris[t].n[e];
      if (nb < 0) continue;
      const std::size_t u = static_cast<std::size_t>(nb);
      if (s.cls[u] != k || s.support[u] != 0) continue;
      s.support[u] = 1;
      s.queue[tail++] = nb;
    }
  }
}

// Marks depth[i] = 1..rings for the patch triangles (support == 1) within
// `rings` edge steps of the patch border, 0 for the core beyond; returns the
// core's triangle count. Breadth-first from the border, explicit queue.
std::size_t erode(std::span<const MeshTriangle> tris, const Scratch& s, int rings) {
  const std::size_t n = tris.size();
  std::size_t head = 0, tail = 0;
  for (std::size_t i = 0; i < n; ++i) {
    s.depth[i] = 0;
    if (s.support[i] != 1) continue;
    for (int e = 0; e < 3; ++e) {
      const std::int32_t nb = tris[i].n[e];
      if (nb < 0 || s.support[static_cast<std::size_t>(nb)] != 1) {
        s.depth[i] = 1;
        s.queue[tail++] = static_cast<std::int32_t>(i);
        break;
      }
    }
  }
  while (head < tail) {
    const std::size_t t = static_cast<std::size_t>(s.queue[head++]);
    if (s.depth[t] >= rings) continue;
    for (int e = 0; e < 3; ++e) {
      const std::int32_t nb = tris[t].n[e];
      if (nb < 0) continue;
      const std::size_t u = static_cast<std::size_t>(nb);
      if (s.support[u] != 1 || s.depth[u] != 0) continue;
      s.depth[u] = static_cast<std::uint8_t>(s.depth[t] + 1);
      s.queue[tail++] = nb;
    }
  }
  std::size_t core = 0;
  for (std::size_t i = 0; i < n; ++i) core += s.support[i] == 1 && s.depth[i] == 0;
  return core;
}

}  // namespace

int cluster_count(int c) {
  return std::min(kMaxClasses, std::max(c + 3, 2 * c));
}

const char* verdict_name(PlaneVerdict v) {
  switch (v) {
    case PlaneVerdict::surplus:
      return "more planes qualify than asked for";
    case PlaneVerdict::accepted:
      return "accepted";
    case PlaneVerdict::faces_away:
      return "faces away from the cameras";
    case PlaneVerdict::too_small:
      return "smaller than the grinder footprint";
    case PlaneVerdict::not_flat:
      return "not flat enough";
    case PlaneVerdict::no_support:
      return "no supporting triangles";
  }
  return "?";
}

Status validate(const GrindParams& p) {
  if (!(p.grinder_diameter_mm > 0.0) || !(p.grinder_diameter_mm < 1000.0))
    return Error::make(Errc::invalid_argument,
                       "grind planes: grinder_diameter_mm %.3g not in (0, 1000)",
                       p.grinder_diameter_mm);
  if (!(p.max_view_angle_deg > 0.0 && p.max_view_angle_deg <= 90.0))
    return Error::make(Errc::invalid_argument,
                       "grind planes: max_view_angle_deg %.3g not in (0, 90]",
                       p.max_view_angle_deg);
  if (!(p.max_rms_mm > 0.0))
    return Error::make(Errc::invalid_argument, "grind planes: max_rms_mm must be > 0");
  if (!(p.inlier_angle_deg > 0.0 && p.inlier_angle_deg < 90.0))
    return Error::make(Errc::invalid_argument, "grind planes: inlier_angle_deg %.3g not in (0, 90)",
                       p.inlier_angle_deg);
  if (!(p.merge_angle_deg >= 0.0 && p.merge_angle_deg < 45.0) || !(p.merge_distance_mm >= 0.0))
    return Error::make(Errc::invalid_argument,
                       "grind planes: merge_angle_deg %.3g or merge_distance_mm %.3g invalid",
                       p.merge_angle_deg, p.merge_distance_mm);
  if (p.edge_rings < 0 || p.edge_rings > 50)
    return Error::make(Errc::invalid_argument, "grind planes: edge_rings %d not in 0..50",
                       p.edge_rings);
  if (!(p.min_trim_band_mm > 0.0))
    return Error::make(Errc::invalid_argument, "grind planes: min_trim_band_mm must be > 0");
  return validate(p.cmeans);
}

std::size_t grind_planes_scratch_bytes(std::size_t n) {
  return 2 * bytes_for<Eigen::Vector3d>(n) + bytes_for<double>(n) + 3 * bytes_for<std::uint8_t>(n) +
         bytes_for<std::int32_t>(n) + bytes_for<Eigen::Vector3d>(kCMeansSamples) +
         bytes_for<std::uint8_t>(kCMeansSamples);
}

Result<GrindResult> find_grind_planes(std::span<const Eigen::Vector3d> xyz,
                                      std::span<const MeshTriangle> tris,
                                      const Eigen::Vector3d& camera, int c,
                                      const GrindParams& params, Arena& arena,
                                      std::span<std::uint8_t> triangle_plane,
                                      std::span<const Eigen::Vector3d> point_normals) {
  PETRA_TRY(validate(params));
  const std::size_t n = tris.size();
  if (c < 1 || c > kMaxClasses)
    return Error::make(Errc::out_of_range, "grind planes: c = %d planes, must be 1..%d", c,
                       kMaxClasses);
  if (triangle_plane.size() != n)
    return Error::make(Errc::invalid_argument, "grind planes: %zu triangles, %zu labels", n,
                       triangle_plane.size());
  if (!point_normals.empty() && point_normals.size() != xyz.size())
    return Error::make(Errc::invalid_argument, "grind planes: %zu points, %zu normals", xyz.size(),
                       point_normals.size());
  if (n < static_cast<std::size_t>(3 * c))
    return Error::make(Errc::degenerate, "grind planes: %zu rock triangles, too few for c = %d", n,
                       c);
  const std::int32_t npts = static_cast<std::int32_t>(xyz.size());
  for (std::size_t i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k)
      if (tris[i].v[k] < 0 || tris[i].v[k] >= npts || tris[i].n[k] < -1 ||
          tris[i].n[k] >= static_cast<std::int64_t>(n))
        return Error::make(Errc::out_of_range, "grind planes: triangle %zu has a bad index", i);

  for (std::size_t i = 0; i < n; ++i) triangle_plane[i] = kNone;
  ArenaScope scope(arena);
  auto scratch = allocate(arena, n);
  if (!scratch) return scratch.error();
  const Scratch& s = *scratch;

  // 1. Triangle geometry, normals towards the camera.
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d& a = xyz[static_cast<std::size_t>(tris[i].v[0])];
    const Eigen::Vector3d& b = xyz[static_cast<std::size_t>(tris[i].v[1])];
    const Eigen::Vector3d& cc = xyz[static_cast<std::size_t>(tris[i].v[2])];
    const Eigen::Vector3d cross = (b - a).cross(cc - a);
    const double len = cross.norm();
    s.centroid[i] = (a + b + cc) / 3.0;
    s.area[i] = 0.5 * len;
    Eigen::Vector3d nrm = len > 0 ? Eigen::Vector3d(cross / len) : Eigen::Vector3d::UnitZ();
    if (!point_normals.empty()) {
      const Eigen::Vector3d& na = point_normals[static_cast<std::size_t>(tris[i].v[0])];
      const Eigen::Vector3d& nb = point_normals[static_cast<std::size_t>(tris[i].v[1])];
      const Eigen::Vector3d& nc = point_normals[static_cast<std::size_t>(tris[i].v[2])];
      const Eigen::Vector3d mean = na + nb + nc;
      if (na.squaredNorm() > 0 && nb.squaredNorm() > 0 && nc.squaredNorm() > 0 && mean.norm() > 1.5)
        nrm = mean.normalized();
    }
    if (nrm.dot(camera - s.centroid[i]) < 0) nrm = -nrm;
    s.normal[i] = nrm;
  }

  GrindResult out;
  // 2. C-means surface classes (eq. 9-12) on the normals, into more classes
  // than the operator's c: a rock shows more faces than the c it is asked
  // for, and c classes would merge two of them into a plane of neither.
  const int k_classes = cluster_count(c);
  Eigen::Vector3d centres[kMaxClasses];
  int k_eff = k_classes;
  {
    // C-means on a regular sample of the triangles (its cost is per sample
    // and per iteration; the angle pass below sees every triangle).
    const std::size_t stride = (n + kCMeansSamples - 1) / kCMeansSamples;
    std::size_t m = 0;
    for (std::size_t i = 0; i < n; i += stride) s.sample[m++] = s.normal[i];
    auto cm = cmeans<double>(std::span<const Eigen::Vector3d>(s.sample.data(), m), k_classes,
                             params.cmeans, s.sample_cls.first(m));
    if (!cm) {
      // All normals equal (one flat face): one class.
      if (cm.code() != Errc::degenerate) return cm.error();
      k_eff = 1;
      centres[0] = s.normal[0];
    } else {
      out.cmeans_iterations = cm->iterations;
      for (int j = 0; j < k_classes; ++j) centres[j] = cm->classes[j].mean;
      out.converged = cm->converged;
    }
  }
  // 3. Angle clustering refinement (centres more than 5 deg apart).
  auto ac = angle_cluster<double>(
      std::span<const Eigen::Vector3d>(s.normal.data(), n),
      std::span<const double>(s.area.data(), n),
      std::span<const Eigen::Vector3d>(centres, static_cast<std::size_t>(k_eff)), params.angle,
      s.cls);
  if (!ac) return ac.error();
  out.angle_iterations = ac->iterations;
  out.converged = (k_eff == 1 || out.converged) && ac->converged;

  // 4. One candidate plane per class; coplanar neighbours merged.
  GrindPlane candidates[kMaxClasses];
  bool alive[kMaxClasses] = {};
  const double cos_inlier = std::cos(params.inlier_angle_deg * M_PI / 180.0);
  const double cos_merge = std::cos(params.merge_angle_deg * M_PI / 180.0);
  auto fit_class = [&](int k) {
    GrindPlane& plane = candidates[k];
    plane = GrindPlane{};
    for (std::size_t i = 0; i < n; ++i)
      if (triangle_plane[i] == k) triangle_plane[i] = kNone;
    largest_patch(tris, s, static_cast<std::uint8_t>(k));
    PlaneFitT<double> fit;
    bool have = false;
    for (int round = 0; round < 3; ++round) {
      auto f = fit_plane_tls_by<double>(
          3 * n,
          [&](std::size_t j) -> const Eigen::Vector3d& {
            return xyz[static_cast<std::size_t>(tris[j / 3].v[j % 3])];
          },
          [&](std::size_t j) { return s.support[j / 3] == 1; });
      if (!f) break;
      fit = *f;
      have = true;
      // Trim the patch to the triangles that agree with the plane.
      const double band = std::max(3.0 * fit.rms, params.min_trim_band_mm);
      Eigen::Vector3d up = fit.plane.normal;
      if (up.dot(camera - fit.centroid) < 0) up = -up;
      for (std::size_t i = 0; i < n; ++i) {
        if (s.support[i] != 1) continue;
        const bool agrees = s.normal[i].dot(up) >= cos_inlier &&
                            std::abs(fit.plane.distance(s.centroid[i])) <= band;
        if (!agrees) s.support[i] = 3;  // dropped
      }
    }
    // The final plane from the patch's core: the matcher's window rounds
    // depth over a few pixels at every crease, so the rings of triangles
    // along the patch's border bend towards the neighbouring faces.
    std::size_t patch = 0, core = erode(tris, s, params.edge_rings);
    for (std::size_t i = 0; i < n; ++i) patch += s.support[i] == 1;
    const bool use_core = core >= 20 && 4 * core >= patch;
    auto in_fit = [&](std::size_t i) {
      return s.support[i] == 1 && (!use_core || s.depth[i] == 0);
    };
    if (have) {
      auto f = fit_plane_tls_by<double>(
          3 * n,
          [&](std::size_t j) -> const Eigen::Vector3d& {
            return xyz[static_cast<std::size_t>(tris[j / 3].v[j % 3])];
          },
          [&](std::size_t j) { return in_fit(j / 3); });
      if (f) fit = *f;
      if (fit.plane.normal.dot(camera - fit.centroid) < 0) {
        fit.plane.normal = -fit.plane.normal;
        fit.plane.d = -fit.plane.d;
      }
    }
    double area = 0, core_area = 0;
    Eigen::Vector3d weighted = Eigen::Vector3d::Zero();
    std::size_t count = 0;
    for (std::size_t i = 0; i < n; ++i) {
      if (s.support[i] != 1) continue;
      area += s.area[i];
      ++count;
      triangle_plane[i] = static_cast<std::uint8_t>(k);
      if (in_fit(i)) {
        weighted += s.area[i] * s.centroid[i];
        core_area += s.area[i];
      }
    }
    plane.triangles = count;
    plane.area_mm2 = area;
    if (!have || count == 0 || !(area > 0) || !(core_area > 0)) {
      plane.verdict = PlaneVerdict::no_support;
      return;
    }
    plane.normal = fit.plane.normal;
    const Eigen::Vector3d centre = weighted / core_area;
    plane.centroid_mm = centre - fit.plane.distance(centre) * fit.plane.normal;  // onto the plane
    plane.rms_mm = fit.rms;
    plane.view_angle_deg = angle_deg(plane.normal, camera - plane.centroid_mm);
    const double footprint = M_PI * params.grinder_diameter_mm * params.grinder_diameter_mm / 4.0;
    if (plane.view_angle_deg > params.max_view_angle_deg) {
      plane.verdict = PlaneVerdict::faces_away;
    } else if (plane.area_mm2 < footprint) {
      plane.verdict = PlaneVerdict::too_small;
    } else if (plane.rms_mm > params.max_rms_mm) {
      plane.verdict = PlaneVerdict::not_flat;
    } else {
      plane.verdict = PlaneVerdict::accepted;
    }
  };
  for (int k = 0; k < ac->c; ++k) {
    alive[k] = ac->count[k] > 0;
    if (alive[k]) fit_class(k);
  }
  // Two classes on one face (its normals spread over both): merge when their
  // planes agree in direction and each centroid lies on the other's plane.
  auto coplanar = [&](int i, int j) {
    const GrindPlane& a = candidates[i];
    const GrindPlane& b = candidates[j];
    if (a.verdict == PlaneVerdict::no_support || b.verdict == PlaneVerdict::no_support)
      return false;
    return a.normal.dot(b.normal) >= cos_merge &&
           std::abs(a.normal.dot(b.centroid_mm - a.centroid_mm)) <= params.merge_distance_mm &&
           std::abs(b.normal.dot(a.centroid_mm - b.centroid_mm)) <= params.merge_distance_mm;
  };
  for (int guard = 0; guard < kMaxClasses; ++guard) {
    bool merged = false;
    for (int i = 0; i < ac->c && !merged; ++i)
      for (int j = i + 1; j < ac->c && !merged; ++j) {
        if (!alive[i] || !alive[j] || !coplanar(i, j)) continue;
        for (std::size_t t = 0; t < n; ++t) {
          if (s.cls[t] == j) s.cls[t] = static_cast<std::uint8_t>(i);
          if (triangle_plane[t] == j) triangle_plane[t] = kNone;
        }
        alive[j] = false;
        fit_class(i);
        ++out.merges;
        merged = true;
      }
    if (!merged) break;
  }
  int distinct = 0;
  for (int k = 0; k < ac->c; ++k) distinct += alive[k];
  out.classes = distinct;

  // 5. Rank: accepted by area (largest first; beyond c they are surplus),
  // then the rejected ones.
  int order[kMaxClasses];
  int m = 0;
  for (int pass = 0; pass < 2; ++pass) {
    const int pass_start = m;
    for (int k = 0; k < ac->c; ++k) {
      if (!alive[k]) continue;
      const bool acc = candidates[k].verdict == PlaneVerdict::accepted;
      if ((pass == 0) != acc) continue;
      int pos = m++;
      order[pos] = k;
      while (pos > pass_start && candidates[order[pos - 1]].area_mm2 < candidates[k].area_mm2) {
        order[pos] = order[pos - 1];
        order[--pos] = k;
      }
    }
    if (pass == 0) {
      out.accepted = std::min(m, c);
      for (int r = out.accepted; r < m; ++r) candidates[order[r]].verdict = PlaneVerdict::surplus;
    }
  }
  out.count = m;
  int rank_of[kMaxClasses];
  for (int k = 0; k < kMaxClasses; ++k) rank_of[k] = -1;
  for (int r = 0; r < m; ++r) {
    out.planes[r] = candidates[order[r]];
    rank_of[order[r]] = r;
  }
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint8_t v = triangle_plane[i];
    triangle_plane[i] =
        v < kMaxClasses && rank_of[v] >= 0 ? static_cast<std::uint8_t>(rank_of[v]) : kNone;
  }
  return out;
}

}  // namespace petra
