#include "algo/propose/flat_discs.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "algo/core/arena.hpp"
#include "algo/surface/grind_qualify.hpp"
#include "algo/surface/plane_fit.hpp"

namespace petra {

namespace {

constexpr int kMaxFaces = 32;  // faces tracked per rock; the largest kMaxClasses reported
constexpr std::uint8_t kNoFace = 0xFF;
constexpr std::uint8_t kKeptFace = 0xFE;  // on a plane the proposal keeps already

struct Face {
  Eigen::Vector3d normal, centre;  // its first disc's plane
  int discs = 0;
};

struct FlatSeed {
  std::size_t tri = 0;  // the seed's free triangle
  double rms_mm = 0;    // its disc's flatness
};

// The free triangles (centroid, area) and what the search keeps per triangle.
struct Free {
  std::span<FaceSample> tri;        // the free triangles, m of them
  std::span<std::uint8_t> face;     // their face, kNoFace: none yet
  std::span<std::int32_t> near;     // one seed's neighbourhood
  std::span<FaceSample> face_tris;  // one face's triangles (qualification)
  std::span<std::int32_t> mesh_of;  // free triangle -> mesh triangle
  std::span<std::int32_t> slot;     // mesh triangle -> free triangle, -1: not free
  std::span<FlatSeed> flat;         // the seeds whose disc is flat
  std::size_t m = 0;
};

Eigen::Vector3d towards(const Eigen::Vector3d& n, const Eigen::Vector3d& from,
                        const Eigen::Vector3d& camera) {
  return n.dot(camera - from) < 0 ? Eigen::Vector3d(-n) : n;
}

// Fits the plane of the listed triangles accepted by `in`, area-weighted.
template <class In>
Result<PlaneFitT<double>> fit_listed(const Free& f, std::size_t count, In&& in) {
  return fit_plane_wtls_by<double>(
      count,
      [&](std::size_t j) -> const Eigen::Vector3d& {
        return f.tri[static_cast<std::size_t>(f.near[j])].p;
      },
      [&](std::size_t j) {
        const FaceSample& s = f.tri[static_cast<std::size_t>(f.near[j])];
        return in(s) ? static_cast<double>(s.area) : 0.0;
      });
}

struct Disc {
  Eigen::Vector3d normal, centre;
  std::size_t count = 0;  // listed in f.near, the disc's first `count`
  double rms_mm = 0;
};

// Step 3: the disc of the tool's radius around seed s; false when it is not
// flat within the tolerance or not covered.
bool flat_disc(Free& f, std::size_t s, const GrindParams& g, const FlatDiscParams& p,
               const Eigen::Vector3d& camera, Disc& disc) {
  const double r = 0.5 * g.grinder_diameter_mm, reach2 = 2.25 * r * r;
  const Eigen::Vector3d seed = f.tri[s].p;
  std::size_t n = 0;
  for (std::size_t i = 0; i < f.m; ++i)
    if ((f.tri[i].p - seed).squaredNorm() <= reach2) f.near[n++] = static_cast<std::int32_t>(i);
  auto ball = fit_listed(f, n, [&](const FaceSample& t) { return (t.p - seed).norm() <= r; });
  if (!ball) return false;
  const Eigen::Vector3d n0 = ball->plane.normal, c0 = ball->centroid;
  auto in_disc = [&](const FaceSample& t) {
    const Eigen::Vector3d q = t.p - c0;
    const double along = q.dot(n0);
    return std::abs(along) <= p.band_mm && q.squaredNorm() - along * along <= r * r;
  };
  auto fit = fit_listed(f, n, in_disc);
  if (!fit || fit->rms > g.max_footprint_rms_mm) return false;
  double covered = 0;
  std::size_t k = 0;
  for (std::size_t j = 0; j < n; ++j) {
    const FaceSample& t = f.tri[static_cast<std::size_t>(f.near[j])];
    if (!in_disc(t)) continue;
    covered += static_cast<double>(t.area);
    f.near[k++] = f.near[j];
  }
  if (covered < g.min_footprint_coverage * std::numbers::pi * r * r) return false;
  disc = {towards(fit->plane.normal, fit->centroid, camera), fit->centroid, k, fit->rms};
  return true;
}

// Whether the disc lies on a plane the proposal keeps (the chain's merge rule).
bool on_kept(const Disc& d, std::span<const GrindPlane> kept, const GrindParams& g) {
  for (const GrindPlane& k : kept)
    if (same_plane(k.normal, k.centroid_mm, d.normal, d.centre, g)) return true;
  return false;
}

// Step 4 for one flat disc: on a kept plane (its triangles explained), on a
// face it shares the plane of, or a new face; its free triangles labelled.
void place_disc(Free& f, const Disc& d, std::span<const GrindPlane> kept, const GrindParams& g,
                Face (&faces)[kMaxFaces], int& count) {
  int k = 0;
  while (k < count && !same_plane(faces[k].normal, faces[k].centre, d.normal, d.centre, g)) ++k;
  std::uint8_t label = static_cast<std::uint8_t>(k);
  if (on_kept(d, kept, g)) {
    label = kKeptFace;
  } else if (k == count) {
    if (count == kMaxFaces) return;
    faces[count++] = Face{d.normal, d.centre, 0};
  }
  if (label != kKeptFace) ++faces[k].discs;
  for (std::size_t j = 0; j < d.count; ++j) {
    std::uint8_t& at = f.face[static_cast<std::size_t>(f.near[j])];
    if (at == kNoFace) at = label;
  }
}

// Steps 2-4: the strided seeds' flat discs, flattest first (a disc across a
// shallow crease is flat within the tolerance but less so than the faces'
// own: they start the faces), each on a face; returns the faces.
int find_faces(Free& f, std::span<const GrindPlane> kept, const GrindParams& g,
               const FlatDiscParams& p, const Eigen::Vector3d& camera, Face (&faces)[kMaxFaces]) {
  const std::size_t seeds = static_cast<std::size_t>(p.max_seeds);
  const std::size_t stride = std::max<std::size_t>(1, (f.m + seeds - 1) / seeds);
  std::size_t n = 0;
  Disc d;
  for (std::size_t s = 0; s < f.m && n < f.flat.size(); s += stride)
    if (flat_disc(f, s, g, p, camera, d)) f.flat[n++] = FlatSeed{s, d.rms_mm};
  std::sort(f.flat.begin(), f.flat.begin() + static_cast<std::ptrdiff_t>(n),
            [](const FlatSeed& a, const FlatSeed& b) { return a.rms_mm < b.rms_mm; });
  int count = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t s = f.flat[i].tri;
    if (f.face[s] != kNoFace || !flat_disc(f, s, g, p, camera, d)) continue;
    place_disc(f, d, kept, g, faces, count);
  }
  return count;
}

Result<Free> take_free(const ReconstructionOutput& r, const RockOnMap& rock,
                       const bool (&explained)[kMaxClasses], double band_mm, int max_seeds,
                       const Eigen::Vector3d& camera, Arena& arena) {
  const std::size_t nt = r.mesh.size();
  auto tri = arena.allocate<FaceSample>(nt, "flat discs' triangles");
  if (!tri) return tri.error();
  auto face = arena.allocate<std::uint8_t>(nt, "flat discs' faces");
  if (!face) return face.error();
  auto near = arena.allocate<std::int32_t>(nt, "flat discs' neighbourhood");
  if (!near) return near.error();
  auto face_tris = arena.allocate<FaceSample>(nt, "flat discs' face");
  if (!face_tris) return face_tris.error();
  auto mesh_of = arena.allocate<std::int32_t>(nt, "flat discs' mesh triangles");
  if (!mesh_of) return mesh_of.error();
  auto slot = arena.allocate<std::int32_t>(nt, "flat discs' slots");
  if (!slot) return slot.error();
  auto flat = arena.allocate<FlatSeed>(static_cast<std::size_t>(max_seeds), "flat discs' seeds");
  if (!flat) return flat.error();
  Free f{*tri, *face, *near, *face_tris, *mesh_of, *slot, *flat, 0};
  for (std::size_t i = 0; i < nt; ++i) {
    const int cls = r.mesh_class[i], k = cls - kVertexPlane0;
    f.slot[i] = -1;
    const bool rockish = cls == kVertexRock || (k >= 0 && k < kMaxClasses);
    if (!rockish || !rock.holds(r, r.mesh[i])) continue;
    const FaceSample sample = triangle_sample(r.xyz_mm, r.mesh[i], camera);
    const Eigen::Vector3d& centre = sample.p;
    if (cls != kVertexRock && k >= 0 && k < kMaxClasses &&
        explained[k]) {  // on a kept plane's patch: explained when on its plane
      const GrindPlane& q = r.planes.planes[k];
      if (std::abs(q.normal.dot(centre - q.centroid_mm)) <= band_mm) continue;
    }
    f.tri[f.m] = sample;
    f.face[f.m] = kNoFace;
    f.mesh_of[f.m] = static_cast<std::int32_t>(i);
    f.slot[i] = static_cast<std::int32_t>(f.m++);
  }
  return f;
}

// Face k's plane from its triangles, area-weighted; gathers them into f.face_tris.
Result<PlaneFitT<double>> face_fit(Free& f, int k, std::size_t& n, double& area) {
  n = 0;
  area = 0;
  for (std::size_t i = 0; i < f.m; ++i)
    if (f.face[i] == k) f.face_tris[n++] = f.tri[i], area += static_cast<double>(f.tri[i].area);
  return fit_plane_wtls_by<double>(
      n, [&](std::size_t j) -> const Eigen::Vector3d& { return f.face_tris[j].p; },
      [&](std::size_t j) { return static_cast<double>(f.face_tris[j].area); });
}

// Face k grown over the mesh's edges: free neighbours within band_mm of its
// plane join it (its discs leave its border, within the tool's radius of a
// crease, out).
void grow_face(Free& f, const ReconstructionOutput& r, int k, const PlaneFitT<double>& fit,
               double band_mm) {
  std::size_t head = 0, tail = 0;
  for (std::size_t i = 0; i < f.m; ++i)
    if (f.face[i] == k) f.near[tail++] = static_cast<std::int32_t>(i);
  while (head < tail) {
    const MeshTriangle& t =
        r.mesh[static_cast<std::size_t>(f.mesh_of[static_cast<std::size_t>(f.near[head++])])];
    for (int e = 0; e < 3; ++e) {
      if (t.n[e] < 0) continue;
      const std::int32_t u = f.slot[static_cast<std::size_t>(t.n[e])];
      if (u < 0 || f.face[static_cast<std::size_t>(u)] != kNoFace) continue;
      if (std::abs(fit.plane.distance(f.tri[static_cast<std::size_t>(u)].p)) > band_mm) continue;
      f.face[static_cast<std::size_t>(u)] = static_cast<std::uint8_t>(k);
      f.near[tail++] = u;
    }
  }
}

// What the chain's checks of a face need besides the face.
struct Qualifier {
  const Eigen::Vector3d& camera;
  const GrindParams& g;
  DepthNoise noise;
  const DiscReach* reach;
};

// Step 5: face k grown over the mesh, its plane from its triangles, then
// the chain's checks.
Status qualify_face(Free& f, const ReconstructionOutput& r, int k, const Qualifier& qf,
                    double max_rms_mm, Arena& arena, GrindPlane& plane) {
  const Eigen::Vector3d& camera = qf.camera;
  const GrindParams& g = qf.g;
  std::size_t n = 0;
  double area = 0;
  plane = GrindPlane{};
  auto first = face_fit(f, k, n, area);
  if (!first) return {};  // degenerate: no support
  grow_face(f, r, k, *first, std::max(3.0 * first->rms, g.min_trim_band_mm));
  auto fit = face_fit(f, k, n, area);
  if (!fit) return {};
  plane.normal = towards(fit->plane.normal, fit->centroid, camera);
  plane.centroid_mm = fit->centroid;
  plane.area_mm2 = area;
  plane.rms_mm = fit->rms;
  plane.triangles = n;
  plane.view_angle_deg = plane_view_angle_deg(plane.normal, plane.centroid_mm, camera);
  Status q = qualify_plane(f.face_tris.first(n), n, camera, g, qf.noise, arena, plane, qf.reach);
  // A face the clustering did not see must be flatter than the tolerance (section 5).
  if (q.ok() && plane.verdict == PlaneVerdict::accepted && plane.footprint_rms_mm > max_rms_mm)
    plane.verdict = PlaneVerdict::too_rough;
  if (!q.ok()) {
    plane.verdict = PlaneVerdict::no_support;
    if (q.code() != Errc::degenerate) return q;
  }
  return {};
}

}  // namespace

Status validate(const FlatDiscParams& p) {
  if (p.max_seeds < 1 || p.max_seeds > 4096)
    return Error::make(Errc::invalid_argument, "flat discs: max_seeds %d not within 1..4096",
                       p.max_seeds);
  if (!(p.band_mm > 0) || !(p.explained_band_mm > 0) || !(p.max_footprint_rms_mm > 0))
    return Error::make(Errc::invalid_argument,
                       "flat discs: band_mm, explained_band_mm, max_footprint_rms_mm not > 0");
  if (p.min_discs < 1)
    return Error::make(Errc::invalid_argument, "flat discs: min_discs %d < 1", p.min_discs);
  return {};
}

std::size_t flat_discs_bytes(std::size_t triangles, int max_seeds) {
  return arena_bytes_for<FlatSeed>(static_cast<std::size_t>(max_seeds)) +
         2 * arena_bytes_for<FaceSample>(triangles) + arena_bytes_for<std::uint8_t>(triangles) +
         3 * arena_bytes_for<std::int32_t>(triangles) + footprint_scratch_bytes(triangles);
}

Result<GrindResult> flat_discs(const StereoRig& rig, const RectifiedPair& rect,
                               const ReconstructionParams& params, const ReconstructionOutput& r,
                               const RockOnMap& rock, const bool (&explained)[kMaxClasses],
                               std::span<const GrindPlane> kept, const FlatDiscParams& discs,
                               const DiscReach* reach, Arena& arena) {
  PETRA_TRY(validate(discs));
  if (r.mesh_class.size() != r.mesh.size())
    return Error::make(Errc::invalid_argument, "flat discs: %zu mesh classes, %zu triangles",
                       r.mesh_class.size(), r.mesh.size());
  ArenaScope scope(arena);
  const Eigen::Vector3d camera = camera_centre_world(rig.left);
  auto f = take_free(r, rock, explained, discs.explained_band_mm, discs.max_seeds, camera, arena);
  if (!f) return f.error();
  const GrindParams& g = params.grind;
  Face faces[kMaxFaces];
  const int count = find_faces(*f, kept, g, discs, camera, faces);
  const DepthNoise noise{rect.left.f_px, rect.baseline_mm, g.sigma_disparity_px,
                         static_cast<double>(params.filter.window)};
  GrindResult out;
  out.footprint_diameter_mm = g.grinder_diameter_mm;
  GrindPlane planes[kMaxFaces];
  int n = 0;
  for (int k = 0; k < count; ++k)
    if (faces[k].discs >= discs.min_discs)
      PETRA_TRY(qualify_face(*f, r, k, {camera, g, noise, reach}, discs.max_footprint_rms_mm, arena,
                             planes[n++]));
  for (int pass = 0; pass < 2; ++pass) {  // accepted by area, then the others
    for (int k = 0; k < n && out.count < kMaxClasses; ++k) {
      int best = -1;
      for (int j = 0; j < n; ++j)
        if (planes[j].triangles > 0 &&
            (planes[j].verdict == PlaneVerdict::accepted) == (pass == 0) &&
            (best < 0 || planes[j].area_mm2 > planes[best].area_mm2))
          best = j;
      if (best < 0) break;
      out.planes[out.count++] = planes[best];
      planes[best].triangles = 0;  // taken
    }
    if (pass == 0) out.accepted = out.count;
  }
  out.classes = count;
  return out;
}

}  // namespace petra
