#include "algo/surface/grind_planes.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "algo/core/arena.hpp"
#include "algo/surface/grind_qualify.hpp"
#include "algo/surface/plane_fit.hpp"

namespace petra {

namespace {

// A split is kept only when it lowers the dispersion by this share (noise
// alone lowers it a little with any extra centre).
constexpr double kSplitGain = 0.02;

constexpr std::uint8_t kNone = 0xFF;

struct Scratch {
  std::span<Eigen::Vector3d> normal, centroid, sample;
  std::span<double> sample_area;
  std::span<std::uint8_t> sample_cls;
  std::span<double> area;
  std::span<std::uint8_t> cls, support, depth;
  std::span<std::int32_t> queue, patch;
  std::span<FaceSample> face;  // one face's patch, core first (step 5)
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
  auto patch = arena.allocate<std::int32_t>(n, "grind planes patch");
  if (!patch) return patch.error();
  s.patch = *patch;
  auto depth = arena.allocate<std::uint8_t>(n, "grind planes border depth");
  if (!depth) return depth.error();
  s.depth = *depth;
  auto queue = arena.allocate<std::int32_t>(n, "grind planes queue");
  if (!queue) return queue.error();
  auto face = arena.allocate<FaceSample>(n, "grind planes face samples");
  if (!face) return face.error();
  s.face = *face;
  auto sample = arena.allocate<Eigen::Vector3d>(kCMeansSamples, "c-means samples");
  if (!sample) return sample.error();
  auto sample_cls = arena.allocate<std::uint8_t>(kCMeansSamples, "c-means sample classes");
  if (!sample_cls) return sample_cls.error();
  s.sample = *sample;
  auto sample_area = arena.allocate<double>(kCMeansSamples, "c-means sample areas");
  if (!sample_area) return sample_area.error();
  s.sample_area = *sample_area;
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

// Marks (support[i] = 1) the largest edge-connected patch of class k, by
// area, lists its triangles in s.patch and returns their count.
// Breadth-first with an explicit queue; `support` doubles as the visited mark
// (2 = visited, not chosen).
std::size_t largest_patch(std::span<const MeshTriangle> tris, const Scratch& s, std::uint8_t k) {
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
  if (best_start == n) return 0;
  std::size_t head = 0, tail = 0;
  s.patch[tail++] = static_cast<std::int32_t>(best_start);
  s.support[best_start] = 1;
  while (head < tail) {
    const std::size_t t = static_cast<std::size_t>(s.patch[head++]);
    for (int e = 0; e < 3; ++e) {
      const std::int32_t nb = tris[t].n[e];
      if (nb < 0) continue;
      const std::size_t u = static_cast<std::size_t>(nb);
      if (s.cls[u] != k || s.support[u] != 0) continue;
      s.support[u] = 1;
      s.patch[tail++] = nb;
    }
  }
  return tail;
}

// Marks depth[i] = 1..rings for the patch triangles (s.patch[0..m) with
// support == 1) within `rings` edge steps of the patch border, 0 for the core
// beyond; returns the core's triangle count. Breadth-first, explicit queue.
std::size_t erode(std::span<const MeshTriangle> tris, const Scratch& s, std::size_t m, int rings) {
  std::size_t head = 0, tail = 0;
  for (std::size_t j = 0; j < m; ++j) s.depth[static_cast<std::size_t>(s.patch[j])] = 0;
  for (std::size_t j = 0; j < m; ++j) {
    const std::size_t i = static_cast<std::size_t>(s.patch[j]);
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
  for (std::size_t j = 0; j < m; ++j) {
    const std::size_t i = static_cast<std::size_t>(s.patch[j]);
    core += s.support[i] == 1 && s.depth[i] == 0;
  }
  return core;
}

}  // namespace

double plane_view_angle_deg(const Eigen::Vector3d& normal, const Eigen::Vector3d& centroid_mm,
                            const Eigen::Vector3d& camera_centre_mm) {
  return angle_deg(normal, camera_centre_mm - centroid_mm);
}

// Area-weighted angular dispersion of a clustering: sum of w (1 - cos) of
// every sample to its class centre (what the angle clustering lowers).
double dispersion(std::span<const Eigen::Vector3d> normals, std::span<const double> weights,
                  std::span<const std::uint8_t> labels, const Eigen::Vector3d* centres) {
  double sum = 0;
  for (std::size_t i = 0; i < normals.size(); ++i)
    sum += weights[i] * (1.0 - normals[i].dot(centres[labels[i]]));
  return sum;
}

// Seeds that split the widest class of a clustering in two along the main
// direction of its normals' spread, in place of its lightest class. False
// when no class spreads over more than `min_sep_rad`.
bool split_seeds(std::span<const Eigen::Vector3d> normals, std::span<const double> weights,
                 std::span<const std::uint8_t> labels, const AngleClusterResultT<double>& r,
                 double min_sep_rad, Eigen::Vector3d* seeds) {
  double spread[kMaxClasses] = {};
  for (std::size_t i = 0; i < normals.size(); ++i)
    spread[labels[i]] += weights[i] * (1.0 - normals[i].dot(r.centres[labels[i]]));
  int wide = 0, light = 0;
  for (int k = 1; k < r.c; ++k) {
    if (spread[k] > spread[wide]) wide = k;
    if (r.weight[k] < r.weight[light]) light = k;
  }
  if (wide == light || !(r.weight[wide] > 0)) return false;
  const Eigen::Vector3d u = r.centres[wide];
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (std::size_t i = 0; i < normals.size(); ++i) {
    if (labels[i] != wide) continue;
    const Eigen::Vector3d t = normals[i] - normals[i].dot(u) * u;  // tangent part
    scatter += weights[i] * t * t.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(scatter);
  const double theta = std::sqrt(std::max(0.0, eig.eigenvalues()(2)) / r.weight[wide]);
  if (!(theta > min_sep_rad)) return false;
  const Eigen::Vector3d e = eig.eigenvectors().col(2);
  for (int k = 0; k < r.c; ++k) seeds[k] = r.centres[k];
  seeds[wide] = (u + std::tan(theta) * e).normalized();
  seeds[light] = (u - std::tan(theta) * e).normalized();
  return true;
}

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
    case PlaneVerdict::too_rough:
      return "too rough over the grinder footprint";
    case PlaneVerdict::too_uncertain:
      return "plane too uncertain for the grinder";
    case PlaneVerdict::no_support:
      return "no supporting triangles";
    case PlaneVerdict::two_faces:
      return "spans two faces (a crease between them)";
  }
  return "?";
}

const char* verdict_key(PlaneVerdict v) {
  switch (v) {
    case PlaneVerdict::surplus:
      return "surplus";
    case PlaneVerdict::accepted:
      return "grindable";
    case PlaneVerdict::faces_away:
      return "faces_away";
    case PlaneVerdict::too_small:
      return "too_small";
    case PlaneVerdict::too_rough:
      return "too_rough";
    case PlaneVerdict::too_uncertain:
      return "too_uncertain";
    case PlaneVerdict::no_support:
      return "no_support";
    case PlaneVerdict::two_faces:
      return "two_faces";
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
  if (!(p.max_footprint_rms_mm > 0.0))
    return Error::make(Errc::invalid_argument, "grind planes: max_footprint_rms_mm must be > 0");
  if (!(p.min_footprint_coverage > 0.0 && p.min_footprint_coverage <= 1.0))
    return Error::make(Errc::invalid_argument,
                       "grind planes: min_footprint_coverage %.3g not in (0, 1]",
                       p.min_footprint_coverage);
  if (!(p.max_normal_sigma_deg > 0.0) || !(p.max_offset_sigma_mm > 0.0) || !(p.agree_sigmas > 0.0))
    return Error::make(Errc::invalid_argument,
                       "grind planes: max_normal_sigma_deg, max_offset_sigma_mm and agree_sigmas "
                       "must be > 0");
  PETRA_TRY(validate(DepthNoise{0, 0, p.sigma_disparity_px, 1}));
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
  if (p.grow_rounds < 0 || p.grow_rounds > 10 ||
      !(p.grow_angle_deg > 0.0 && p.grow_angle_deg < 90.0))
    return Error::make(Errc::invalid_argument,
                       "grind planes: grow_rounds %d not in 0..10 or grow_angle_deg %.3g not in "
                       "(0, 90)",
                       p.grow_rounds, p.grow_angle_deg);
  if (!(p.min_trim_band_mm > 0.0))
    return Error::make(Errc::invalid_argument, "grind planes: min_trim_band_mm must be > 0");
  return validate(p.cmeans);
}

std::size_t grind_planes_scratch_bytes(std::size_t n) {
  return 2 * arena_bytes_for<Eigen::Vector3d>(n) + arena_bytes_for<double>(n) +
         3 * arena_bytes_for<std::uint8_t>(n) + 2 * arena_bytes_for<std::int32_t>(n) +
         arena_bytes_for<Eigen::Vector3d>(kCMeansSamples) +
         arena_bytes_for<std::uint8_t>(kCMeansSamples) + arena_bytes_for<double>(kCMeansSamples) +
         arena_bytes_for<FaceSample>(n) + footprint_scratch_bytes(n);
}

namespace {

// The mesh and label spans agree with each other and with c.
Status check_mesh(std::span<const Eigen::Vector3d> xyz, std::span<const MeshTriangle> tris, int c,
                  std::span<const std::uint8_t> triangle_plane,
                  std::span<const Eigen::Vector3d> point_normals) {
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
  if (n < 3 * static_cast<std::size_t>(c))
    return Error::make(Errc::degenerate, "grind planes: %zu rock triangles, too few for c = %d", n,
                       c);
  const std::int32_t npts = static_cast<std::int32_t>(xyz.size());
  for (std::size_t i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k)
      if (tris[i].v[k] < 0 || tris[i].v[k] >= npts || tris[i].n[k] < -1 ||
          tris[i].n[k] >= static_cast<std::int64_t>(n))
        return Error::make(Errc::out_of_range, "grind planes: triangle %zu has a bad index", i);
  return ok_status();
}

// 1. Triangle geometry, normals towards the camera.
void triangle_geometry(std::span<const Eigen::Vector3d> xyz, std::span<const MeshTriangle> tris,
                       const Eigen::Vector3d& camera,
                       std::span<const Eigen::Vector3d> point_normals, const Scratch& s) {
  for (std::size_t i = 0; i < tris.size(); ++i) {
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
}

// C-means and the angle pass iterate on a regular sample of the triangles
// (their cost is per sample and per iteration); then every triangle joins
// the nearest final centre. Returns the sample's size.
std::size_t take_samples(const Scratch& s, std::size_t n) {
  const std::size_t stride = (n + kCMeansSamples - 1) / kCMeansSamples;
  std::size_t m = 0;
  for (std::size_t i = 0; i < n; i += stride) {
    s.sample[m] = s.normal[i];
    s.sample_area[m] = s.area[i];
    ++m;
  }
  return m;
}

// 2. C-means surface classes (eq. 9-12) on the m sampled normals; returns
// how many centres it leaves (one when all normals are equal).
Result<int> cmeans_centres(const Scratch& s, std::size_t m, int k_classes,
                           const GrindParams& params, Eigen::Vector3d* centres, GrindResult& out) {
  auto cm = cmeans<double>(std::span<const Eigen::Vector3d>(s.sample.data(), m), k_classes,
                           params.cmeans, s.sample_cls.first(m));
  if (!cm) {
    // All normals equal (one flat face): one class.
    if (cm.code() != Errc::degenerate) return cm.error();
    centres[0] = s.normal[0];
    return 1;
  }
  out.cmeans_iterations = cm->iterations;
  for (int j = 0; j < k_classes; ++j) centres[j] = cm->classes[j].mean;
  out.converged = cm->converged;
  return k_classes;
}

// Petra adds: C-means can leave two faces in one broad class (its
// log-determinant term tolerates a wide class) and the angle pass keeps
// them there, with a centre between the faces. Split the widest class in
// place of the lightest while that lowers the angular dispersion.
void split_wide_classes(const Scratch& s, std::size_t m, int k_classes, const GrindParams& params,
                        AngleClusterResultT<double>& ac, GrindResult& out) {
  const std::span<const Eigen::Vector3d> sn(s.sample.data(), m);
  const std::span<const double> sw(s.sample_area.data(), m);
  std::uint8_t trial_labels[kCMeansSamples];
  const std::span<std::uint8_t> tl(trial_labels, m);
  double best = dispersion(sn, sw, s.sample_cls.first(m), ac.centres);
  const double min_sep = params.angle.min_separation_deg * M_PI / 180.0;
  for (int attempt = 0; attempt < k_classes; ++attempt) {
    Eigen::Vector3d seeds[kMaxClasses];
    if (ac.c < 2 || !split_seeds(sn, sw, s.sample_cls.first(m), ac, min_sep, seeds)) break;
    auto trial = angle_cluster<double>(
        sn, sw, std::span<const Eigen::Vector3d>(seeds, static_cast<std::size_t>(ac.c)),
        params.angle, tl);
    if (!trial) break;
    const double d = dispersion(sn, sw, tl, trial->centres);
    if (!(d < best * (1.0 - kSplitGain))) break;
    best = d;
    ac = *trial;
    std::copy(tl.begin(), tl.end(), s.sample_cls.begin());
    ++out.splits;
  }
}

// 2-3. Surface classes of the normals: c-means into more classes than the
// operator's c (a rock shows more faces than the c it is asked for, and c
// classes would merge two of them into a plane of neither), refined by
// angle clustering and splitting. Every triangle joins the nearest centre
// (s.cls); members counts them by class.
Result<AngleClusterResultT<double>> surface_classes(const Scratch& s, std::size_t n, int c,
                                                    const GrindParams& params, std::size_t* members,
                                                    GrindResult& out) {
  const int k_classes = cluster_count(c);
  Eigen::Vector3d centres[kMaxClasses];
  const std::size_t m = take_samples(s, n);
  auto k_eff = cmeans_centres(s, m, k_classes, params, centres, out);
  if (!k_eff) return k_eff.error();
  // 3. Angle clustering refinement (4b; centres more than 5 deg apart),
  // area-weighted.
  auto ac = angle_cluster<double>(
      std::span<const Eigen::Vector3d>(s.sample.data(), m),
      std::span<const double>(s.sample_area.data(), m),
      std::span<const Eigen::Vector3d>(centres, static_cast<std::size_t>(*k_eff)), params.angle,
      s.sample_cls.first(m));
  if (!ac) return ac.error();
  out.angle_iterations = ac->iterations;
  out.converged = (*k_eff == 1 || out.converged) && ac->converged;
  split_wide_classes(s, m, k_classes, params, *ac, out);
  for (std::size_t i = 0; i < n; ++i) {
    int best = 0;
    double best_cos = s.normal[i].dot(ac->centres[0]);
    for (int k = 1; k < ac->c; ++k) {
      const double d = s.normal[i].dot(ac->centres[k]);
      if (d > best_cos) {
        best_cos = d;
        best = k;
      }
    }
    s.cls[i] = static_cast<std::uint8_t>(best);
    ++members[best];
  }
  return ac;
}

// Step 4's plane of one class and step 5's verdict on it, with what every
// class shares. A failure other than a degenerate patch (a budget, a bad
// parameter) is kept in `failure`: the last one is returned.
struct ClassFitter {
  std::span<const Eigen::Vector3d> xyz;
  std::span<const MeshTriangle> tris;
  const Scratch& s;
  const Eigen::Vector3d& camera;
  const GrindParams& params;
  Arena& arena;
  std::span<std::uint8_t> triangle_plane;
  DepthNoise noise;
  double cos_inlier = 0, cos_grow = 0;
  const DiscReach* reach = nullptr;  // the footprint's (find_grind_planes)
  bool use_core = false;             // the final fit uses the patch's core only
  Status failure{};

  // Vertex j % 3 of patch triangle j / 3.
  const Eigen::Vector3d& vertex(std::size_t j) const {
    return xyz[static_cast<std::size_t>(tris[static_cast<std::size_t>(s.patch[j / 3])].v[j % 3])];
  }
  std::size_t tri_of(std::size_t j) const { return static_cast<std::size_t>(s.patch[j]); }
  bool in_fit(std::size_t i) const { return s.support[i] == 1 && (!use_core || s.depth[i] == 0); }
  double band_of(const PlaneFitT<double>& fit) const {
    return std::max(3.0 * fit.rms, params.min_trim_band_mm);
  }
  Eigen::Vector3d up_of(const PlaneFitT<double>& fit) const {
    Eigen::Vector3d up = fit.plane.normal;
    if (up.dot(camera - fit.centroid) < 0) up = -up;
    return up;
  }

  // Fits the patch's first pm triangles, trimming those that disagree with
  // the plane, three times. False when no plane fits.
  bool trimmed_fit(std::size_t pm, PlaneFitT<double>& fit) const {
    auto vtx = [this](std::size_t j) -> const Eigen::Vector3d& { return vertex(j); };
    bool have = false;
    for (int round = 0; round < 3; ++round) {
      auto f = fit_plane_tls_by<double>(
          3 * pm, vtx, [&](std::size_t j) { return s.support[tri_of(j / 3)] == 1; });
      if (!f) break;
      fit = *f;
      have = true;
      // Trim the patch to the triangles that agree with the plane.
      const double band = band_of(fit);
      const Eigen::Vector3d up = up_of(fit);
      for (std::size_t j = 0; j < pm; ++j) {
        const std::size_t i = tri_of(j);
        if (s.support[i] != 1) continue;
        const bool agrees = s.normal[i].dot(up) >= cos_inlier &&
                            std::abs(fit.plane.distance(s.centroid[i])) <= band;
        if (!agrees) s.support[i] = 3;  // dropped
      }
    }
    return have;
  }

  // Regrow: a steep face's matched disparity is a staircase, whose treads
  // and risers cluster into different normal classes, so the class patch
  // holds the treads only and its plane leans towards them. The face is
  // taken back by position: edge neighbours of the patch that lie within
  // the distance band of its plane and within grow_angle_deg of its normal
  // join it (from any class), and the plane is refitted on the whole set.
  // Returns the patch's new length.
  std::size_t regrow(std::size_t pm, PlaneFitT<double>& fit) const {
    auto vtx = [this](std::size_t j) -> const Eigen::Vector3d& { return vertex(j); };
    std::size_t pn = pm;
    for (int round = 0; round < params.grow_rounds; ++round) {
      const double band = band_of(fit);
      const Eigen::Vector3d up = up_of(fit);
      // Marks: 1 in the patch, 3 trimmed (listed in s.patch), 4 + round
      // looked at and left out this round (largest_patch clears them all).
      const std::uint8_t looked = static_cast<std::uint8_t>(4 + round);
      std::size_t head = 0, tail = 0;
      for (std::size_t j = 0; j < pn; ++j)
        if (s.support[tri_of(j)] == 1) s.queue[tail++] = s.patch[j];
      while (head < tail) {
        const std::size_t t = static_cast<std::size_t>(s.queue[head++]);
        for (int e = 0; e < 3; ++e) {
          const std::int32_t nb = tris[t].n[e];
          if (nb < 0) continue;
          const std::size_t u = static_cast<std::size_t>(nb);
          if (s.support[u] == 1 || s.support[u] == looked) continue;
          const bool joins = s.normal[u].dot(up) >= cos_grow &&
                             std::abs(fit.plane.distance(s.centroid[u])) <= band;
          if (!joins) {
            if (s.support[u] != 3) s.support[u] = looked;
            continue;
          }
          if (s.support[u] != 3) s.patch[pn++] = nb;  // not listed yet
          s.support[u] = 1;
          s.queue[tail++] = nb;
        }
      }
      auto f = fit_plane_tls_by<double>(
          3 * pn, vtx, [&](std::size_t j) { return s.support[tri_of(j / 3)] == 1; });
      if (!f) break;
      fit = *f;
    }
    return pn;
  }

  // The final plane from the patch's core: the matcher's window rounds
  // depth over a few pixels at every crease, so the rings of triangles
  // along the patch's border bend towards the neighbouring faces. Sets
  // use_core.
  void choose_core(std::size_t pm) {
    std::size_t patch = 0;
    const std::size_t core = erode(tris, s, pm, params.edge_rings);
    for (std::size_t j = 0; j < pm; ++j) patch += s.support[tri_of(j)] == 1;
    use_core = core >= 20 && 4 * core >= patch;
  }

  // The final fit: least squares along the viewing ray to the patch (the
  // stereo error model, fit_along_ray), or total least squares; normal
  // towards the camera.
  void final_fit(std::size_t pm, PlaneFitT<double>& fit) const {
    auto vtx = [this](std::size_t j) -> const Eigen::Vector3d& { return vertex(j); };
    const Eigen::Vector3d ray = (fit.centroid - camera).normalized();
    auto use = [&](std::size_t j) { return in_fit(tri_of(j / 3)) ? 1.0 : 0.0; };
    auto f = params.fit_along_ray ? fit_plane_along_by<double>(3 * pm, vtx, use, ray)
                                  : fit_plane_wtls_by<double>(3 * pm, vtx, use);
    if (f) fit = *f;
    if (fit.plane.normal.dot(camera - fit.centroid) < 0) {
      fit.plane.normal = -fit.plane.normal;
      fit.plane.d = -fit.plane.d;
    }
  }

  struct Claimed {
    double area = 0, core_area = 0;
    Eigen::Vector3d weighted = Eigen::Vector3d::Zero();  // core centroids by area
    std::size_t count = 0;
  };

  // Labels the patch's triangles with class k and sums them up.
  Claimed claim(int k, std::size_t pm) const {
    Claimed cl;
    for (std::size_t j = 0; j < pm; ++j) {
      const std::size_t i = tri_of(j);
      if (s.support[i] != 1) continue;
      // A triangle regrown into two faces' patches (at a crease) is counted
      // by the first only.
      if (triangle_plane[i] != kNone && triangle_plane[i] != k) continue;
      cl.area += s.area[i];
      ++cl.count;
      triangle_plane[i] = static_cast<std::uint8_t>(k);
      if (in_fit(i)) {
        cl.weighted += s.area[i] * s.centroid[i];
        cl.core_area += s.area[i];
      }
    }
    return cl;
  }

  // 5. Where the grinder sits, the plane's uncertainty, the verdict.
  void qualify(int k, std::size_t pm, GrindPlane& plane) {
    std::size_t faces = 0, core_faces = 0;
    for (int pass = 0; pass < 2; ++pass)  // the fit's core first, then the border
      for (std::size_t j = 0; j < pm; ++j) {
        const std::size_t i = tri_of(j);
        if (s.support[i] != 1 || triangle_plane[i] != k || in_fit(i) != (pass == 0)) continue;
        s.face[faces++] = triangle_sample(xyz, tris[i], camera);
        if (pass == 0) ++core_faces;
      }
    Status q =
        qualify_plane(s.face.first(faces), core_faces, camera, params, noise, arena, plane, reach);
    if (!q.ok()) {
      plane.verdict = PlaneVerdict::no_support;
      if (q.code() != Errc::degenerate) failure = q;  // a budget or a bad parameter: fail
    }
  }

  // Moments of one half's triangle centroids, about the patch centre.
  struct HalfMoments {
    double count = 0;
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    Eigen::Matrix3d outer = Eigen::Matrix3d::Zero();
    // Total-least-squares normal (the scatter's least axis); false when too
    // few points or collinear.
    bool normal(Eigen::Vector3d& n) const {
      if (count < 3) return false;
      const Eigen::Vector3d mean = sum / count;
      const Eigen::Matrix3d cov = outer / count - mean * mean.transpose();
      const SymEigen3<double> e = sym_eigen3<double>(cov);  // ascending
      if (!(e.values(1) > kCollinearEigenRatio * e.values(2))) return false;
      n = e.vectors.col(0).normalized();
      return true;
    }
  };

  // A patch over two faces: a class of the normals between two faces holds
  // the rounded crease between them (a strip of each), and its plane lies
  // between the faces; regrown, it spreads over one of them and tilts
  // towards the other (realistic scene 03's top face, 9.96 deg; docs/log.md).
  // Its halves, split through the centroid across any of four in-plane
  // directions, then differ by more than a regrowth bridges (grow_angle_deg);
  // one face's halves differ by its noise and bend (up to 9.4 deg among the
  // planes reported on the clean and realistic sets). One pass: each half's
  // moments.
  bool spans_two_faces(std::size_t pm, const PlaneFitT<double>& fit) const {
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    double area = 0;
    for (std::size_t j = 0; j < pm; ++j) {
      const std::size_t i = tri_of(j);
      if (!in_fit(i)) continue;
      centre += s.area[i] * s.centroid[i];
      area += s.area[i];
    }
    if (!(area > 0)) return false;
    centre /= area;
    const Eigen::Vector3d e1 = fit.plane.normal.unitOrthogonal();
    const Eigen::Vector3d e2 = fit.plane.normal.cross(e1);
    Eigen::Vector3d dir[4];
    for (int d = 0; d < 4; ++d) dir[d] = std::cos(d * M_PI / 4) * e1 + std::sin(d * M_PI / 4) * e2;
    HalfMoments half[4][2];  // triangle centroids: a third of the vertex list's cost
    for (std::size_t j = 0; j < pm; ++j) {
      const std::size_t i = tri_of(j);
      if (!in_fit(i)) continue;
      const Eigen::Vector3d q = s.centroid[i] - centre;
      const Eigen::Matrix3d qq = q * q.transpose();
      for (int d = 0; d < 4; ++d) {
        HalfMoments& h = half[d][q.dot(dir[d]) > 0 ? 0 : 1];
        h.count += 1;
        h.sum += q;
        h.outer += qq;
      }
    }
    for (int d = 0; d < 4; ++d) {
      Eigen::Vector3d a, b;
      if (!half[d][0].normal(a) || !half[d][1].normal(b)) continue;
      if (std::min(angle_deg(a, b), angle_deg(a, -b)) > params.grow_angle_deg) return true;
    }
    return false;
  }

  // A class whose patch spans two faces has no plane of its own: refused
  // (two_faces), its triangles left for the faces' own classes to regrow
  // into and claim.
  void refuse_two_faces(const PlaneFitT<double>& fit, GrindPlane& plane) const {
    plane.verdict = PlaneVerdict::two_faces;
    plane.normal = plane.face_normal = up_of(fit);
    plane.centroid_mm = plane.face_centroid_mm = fit.centroid;
    plane.rms_mm = fit.rms;
  }

  // 4. The plane of class k from its largest patch.
  void fit_class(int k, GrindPlane& plane) {
    plane = GrindPlane{};
    for (std::size_t i = 0; i < triangle_plane.size(); ++i)
      if (triangle_plane[i] == k) triangle_plane[i] = kNone;
    std::size_t pm = largest_patch(tris, s, static_cast<std::uint8_t>(k));
    PlaneFitT<double> fit;
    const bool have = trimmed_fit(pm, fit);
    use_core = false;  // the two-face test sees the whole trimmed patch
    if (have && spans_two_faces(pm, fit)) {
      refuse_two_faces(fit, plane);  // not regrown: it would spread over one face
      return;
    }
    if (have) pm = regrow(pm, fit);
    choose_core(pm);
    if (have) final_fit(pm, fit);
    if (have && spans_two_faces(pm, fit)) {  // regrown over a crease
      refuse_two_faces(fit, plane);
      return;
    }
    const Claimed cl = claim(k, pm);
    plane.triangles = cl.count;
    plane.area_mm2 = cl.area;
    if (!have || cl.count == 0 || !(cl.area > 0) || !(cl.core_area > 0)) {
      plane.verdict = PlaneVerdict::no_support;
      return;
    }
    plane.normal = fit.plane.normal;
    const Eigen::Vector3d centre = cl.weighted / cl.core_area;
    plane.centroid_mm = centre - fit.plane.distance(centre) * fit.plane.normal;  // onto the plane
    plane.rms_mm = fit.rms;
    plane.view_angle_deg = plane_view_angle_deg(plane.normal, plane.centroid_mm, camera);
    qualify(k, pm, plane);
  }
};

// Two classes on one face (its normals spread over both), by the whole
// patches' planes (the reported ones may be a footprint's).
bool coplanar(const GrindPlane& a, const GrindPlane& b, const GrindParams& params) {
  auto planeless = [](PlaneVerdict v) {
    return v == PlaneVerdict::no_support || v == PlaneVerdict::two_faces;
  };
  if (planeless(a.verdict) || planeless(b.verdict)) return false;
  return same_plane(a.face_normal, a.face_centroid_mm, b.face_normal, b.face_centroid_mm, params);
}

// Merges coplanar classes, one pair at a time (each merge refits the
// survivor, which may then match another); returns the merges.
int merge_coplanar(ClassFitter& fitter, int classes, GrindPlane* candidates, bool* alive) {
  const Scratch& s = fitter.s;
  int merges = 0;
  for (int guard = 0; guard < kMaxClasses; ++guard) {
    bool merged = false;
    for (int i = 0; i < classes && !merged; ++i)
      for (int j = i + 1; j < classes && !merged; ++j) {
        if (!alive[i] || !alive[j] || !coplanar(candidates[i], candidates[j], fitter.params))
          continue;
        for (std::size_t t = 0; t < s.cls.size(); ++t) {
          if (s.cls[t] == j) s.cls[t] = static_cast<std::uint8_t>(i);
          if (fitter.triangle_plane[t] == j) fitter.triangle_plane[t] = kNone;
        }
        alive[j] = false;
        fitter.fit_class(i, candidates[i]);
        ++merges;
        merged = true;
      }
    if (!merged) break;
  }
  return merges;
}

// 5. Rank: accepted by area (largest first; beyond c they are surplus),
// then the rejected ones; triangle labels become ranks.
void rank_planes(int c, int classes, GrindPlane* candidates, const bool* alive,
                 std::span<std::uint8_t> triangle_plane, GrindResult& out) {
  int order[kMaxClasses] = {};
  bool qualified[kMaxClasses] = {};  // ranked in pass 0 (accepted or surplus): not again
  for (int k = 0; k < classes; ++k) qualified[k] = candidates[k].verdict == PlaneVerdict::accepted;
  int ranked = 0;
  for (int pass = 0; pass < 2; ++pass) {
    const int pass_start = ranked;
    for (int k = 0; k < classes; ++k) {
      if (!alive[k]) continue;
      if ((pass == 0) != qualified[k]) continue;
      int pos = ranked++;
      order[pos] = k;
      while (pos > pass_start && candidates[order[pos - 1]].area_mm2 < candidates[k].area_mm2) {
        order[pos] = order[pos - 1];
        order[--pos] = k;
      }
    }
    if (pass == 0) {
      out.accepted = std::min(ranked, c);
      for (int r = out.accepted; r < ranked; ++r)
        candidates[order[r]].verdict = PlaneVerdict::surplus;
    }
  }
  out.count = ranked;
  int rank_of[kMaxClasses];
  for (int k = 0; k < kMaxClasses; ++k) rank_of[k] = -1;
  for (int r = 0; r < ranked; ++r) {
    out.planes[r] = candidates[order[r]];
    rank_of[order[r]] = r;
  }
  for (std::size_t i = 0; i < triangle_plane.size(); ++i) {
    const std::uint8_t v = triangle_plane[i];
    triangle_plane[i] =
        v < kMaxClasses && rank_of[v] >= 0 ? static_cast<std::uint8_t>(rank_of[v]) : kNone;
  }
}

}  // namespace

Result<GrindResult> find_grind_planes(std::span<const Eigen::Vector3d> xyz,
                                      std::span<const MeshTriangle> tris,
                                      const Eigen::Vector3d& camera, int c,
                                      const GrindParams& params, Arena& arena,
                                      std::span<std::uint8_t> triangle_plane,
                                      std::span<const Eigen::Vector3d> point_normals,
                                      const RigGeometry& rig, const DiscReach* reach) {
  PETRA_TRY(validate(params));
  PETRA_TRY(check_mesh(xyz, tris, c, triangle_plane, point_normals));
  const std::size_t n = tris.size();
  for (std::size_t i = 0; i < n; ++i) triangle_plane[i] = kNone;
  ArenaScope scope(arena);
  auto scratch = allocate(arena, n);
  if (!scratch) return scratch.error();
  const Scratch& s = *scratch;

  triangle_geometry(xyz, tris, camera, point_normals, s);
  GrindResult out;
  out.footprint_diameter_mm = params.grinder_diameter_mm;
  std::size_t members[kMaxClasses] = {};
  auto ac = surface_classes(s, n, c, params, members, out);
  if (!ac) return ac.error();

  // 4. One candidate plane per class; coplanar neighbours merged.
  GrindPlane candidates[kMaxClasses];
  bool alive[kMaxClasses] = {};
  ClassFitter fitter{
      xyz,
      tris,
      s,
      camera,
      params,
      arena,
      triangle_plane,
      DepthNoise{rig.focal_px, rig.baseline_mm, params.sigma_disparity_px, rig.correlation_px},
      std::cos(params.inlier_angle_deg * M_PI / 180.0),
      std::cos(params.grow_angle_deg * M_PI / 180.0),
      reach};
  for (int k = 0; k < ac->c; ++k) {
    alive[k] = members[k] > 0;
    if (alive[k]) fitter.fit_class(k, candidates[k]);
  }
  out.merges += merge_coplanar(fitter, ac->c, candidates, alive);
  if (!fitter.failure.ok()) return fitter.failure.error();
  int distinct = 0;
  for (int k = 0; k < ac->c; ++k) distinct += alive[k];
  out.classes = distinct;
  rank_planes(c, ac->c, candidates, alive, triangle_plane, out);
  return out;
}

bool same_plane(const Eigen::Vector3d& na, const Eigen::Vector3d& ca, const Eigen::Vector3d& nb,
                const Eigen::Vector3d& cb, const GrindParams& p) {
  return na.dot(nb) >= std::cos(p.merge_angle_deg * M_PI / 180.0) &&
         std::abs(na.dot(cb - ca)) <= p.merge_distance_mm &&
         std::abs(nb.dot(ca - cb)) <= p.merge_distance_mm;
}

}  // namespace petra
