#include "algo/grind_planes.hpp"

#include <Eigen/Geometry>
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
  std::span<std::uint8_t> cls, support;
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

}  // namespace

const char* verdict_name(PlaneVerdict v) {
  switch (v) {
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
  if (!(p.min_trim_band_mm > 0.0))
    return Error::make(Errc::invalid_argument, "grind planes: min_trim_band_mm must be > 0");
  return validate(p.cmeans);
}

std::size_t grind_planes_scratch_bytes(std::size_t n) {
  return 2 * bytes_for<Eigen::Vector3d>(n) + bytes_for<double>(n) + 2 * bytes_for<std::uint8_t>(n) +
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
  // 2. C-means surface classes (eq. 9-12) on the normals.
  Eigen::Vector3d centres[kMaxClasses];
  int c_eff = c;
  if (c == 1) {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (std::size_t i = 0; i < n; ++i) sum += s.area[i] * s.normal[i];
    centres[0] = sum;
  } else {
    // C-means on a regular sample of the triangles (its cost is per sample
    // and per iteration; the angle pass below sees every triangle).
    const std::size_t stride = (n + kCMeansSamples - 1) / kCMeansSamples;
    std::size_t m = 0;
    for (std::size_t i = 0; i < n; i += stride) s.sample[m++] = s.normal[i];
    auto cm = cmeans<double>(std::span<const Eigen::Vector3d>(s.sample.data(), m), c, params.cmeans,
                             s.sample_cls.first(m));
    if (!cm) {
      // All normals equal (one flat face): one class, and the angle pass says so.
      if (cm.code() != Errc::degenerate) return cm.error();
      c_eff = 1;
      centres[0] = s.normal[0];
    } else {
      out.cmeans_iterations = cm->iterations;
      for (int j = 0; j < c; ++j) centres[j] = cm->classes[j].mean;
      out.converged = cm->converged;
    }
  }
  // 3. Angle clustering refinement.
  auto ac = angle_cluster<double>(
      std::span<const Eigen::Vector3d>(s.normal.data(), n),
      std::span<const double>(s.area.data(), n),
      std::span<const Eigen::Vector3d>(centres, static_cast<std::size_t>(c_eff)), params.angle,
      s.cls);
  if (!ac) return ac.error();
  out.angle_iterations = ac->iterations;
  out.classes = ac->c;
  out.converged = (c_eff == 1 || out.converged) && ac->converged;

  // 4. One candidate plane per class.
  GrindPlane candidates[kMaxClasses];
  const double cos_inlier = std::cos(params.inlier_angle_deg * M_PI / 180.0);
  for (int k = 0; k < ac->c; ++k) {
    GrindPlane& plane = candidates[k];
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
      if (fit.plane.normal.dot(camera - fit.centroid) < 0) {
        fit.plane.normal = -fit.plane.normal;
        fit.plane.d = -fit.plane.d;
      }
      if (round == 2) break;
      // Trim the patch to the triangles that agree with the plane.
      const double band = std::max(3.0 * fit.rms, params.min_trim_band_mm);
      for (std::size_t i = 0; i < n; ++i) {
        if (s.support[i] != 1) continue;
        const bool agrees = s.normal[i].dot(fit.plane.normal) >= cos_inlier &&
                            std::abs(fit.plane.distance(s.centroid[i])) <= band;
        if (!agrees) s.support[i] = 3;  // dropped
      }
    }
    // Support statistics and the triangle labels for this class.
    double area = 0;
    Eigen::Vector3d weighted = Eigen::Vector3d::Zero();
    std::size_t count = 0;
    for (std::size_t i = 0; i < n; ++i) {
      if (s.support[i] != 1) continue;
      area += s.area[i];
      weighted += s.area[i] * s.centroid[i];
      ++count;
    }
    plane.triangles = count;
    plane.area_mm2 = area;
    if (!have || count == 0 || !(area > 0)) {
      plane.verdict = PlaneVerdict::no_support;
      continue;
    }
    plane.normal = fit.plane.normal;
    const Eigen::Vector3d centre = weighted / area;
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
    // Remember which triangles support class k (labels rewritten below).
    for (std::size_t i = 0; i < n; ++i)
      if (s.support[i] == 1) s.support[i] = static_cast<std::uint8_t>(16 + k);
    for (std::size_t i = 0; i < n; ++i)
      if (s.support[i] >= 16) triangle_plane[i] = s.support[i];
  }

  // 5. Rank: accepted by area (largest first), then the rejected ones.
  int order[kMaxClasses];
  int m = 0;
  for (int pass = 0; pass < 2; ++pass)
    for (int k = 0; k < ac->c; ++k) {
      const bool acc = candidates[k].verdict == PlaneVerdict::accepted;
      if ((pass == 0) != acc) continue;
      int pos = m++;
      order[pos] = k;
      // Insertion by area within the pass.
      const int pass_start = pass == 0 ? 0 : out.accepted;
      while (pos > pass_start && candidates[order[pos - 1]].area_mm2 < candidates[k].area_mm2) {
        order[pos] = order[pos - 1];
        order[--pos] = k;
      }
      if (pass == 0) ++out.accepted;
    }
  out.count = m;
  int rank_of[kMaxClasses];
  for (int r = 0; r < m; ++r) {
    out.planes[r] = candidates[order[r]];
    rank_of[order[r]] = r;
  }
  // triangle_plane holds 16 + class for supporting triangles (from the loop
  // above) and stale values elsewhere: rewrite all.
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint8_t v = triangle_plane[i];
    bool supports = false;
    for (int k = 0; k < ac->c; ++k) supports |= v == 16 + k;
    triangle_plane[i] = supports ? static_cast<std::uint8_t>(rank_of[v - 16]) : kNone;
  }
  return out;
}

}  // namespace petra
