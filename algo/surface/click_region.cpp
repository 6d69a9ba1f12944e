#include "algo/surface/click_region.hpp"

#include <cmath>
#include <cstdint>

namespace petra {

namespace {

constexpr double kDegToRad = 3.14159265358979323846 / 180.0;

// Vertex -> incident triangles (compressed rows): first[v] .. first[v + 1].
struct Incidence {
  std::span<std::uint32_t> first;  // points + 1
  std::span<std::uint32_t> tris;   // 3 per triangle
};

Result<Incidence> build_incidence(std::size_t points, std::span<const MeshTriangle> mesh,
                                  Arena& arena) {
  auto first = arena.allocate<std::uint32_t>(points + 1, "click region: vertex rows");
  if (!first) return first.error();
  auto tris = arena.allocate_uninitialised<std::uint32_t>(3 * mesh.size(), "click region: rows");
  if (!tris) return tris.error();
  for (const MeshTriangle& t : mesh)
    for (int k = 0; k < 3; ++k) ++(*first)[static_cast<std::size_t>(t.v[k]) + 1];
  for (std::size_t v = 0; v < points; ++v) (*first)[v + 1] += (*first)[v];
  // Fill using first[v] as a cursor, then shift the rows back.
  for (std::size_t i = 0; i < mesh.size(); ++i)
    for (int k = 0; k < 3; ++k)
      (*tris)[(*first)[static_cast<std::size_t>(mesh[i].v[k])]++] = static_cast<std::uint32_t>(i);
  for (std::size_t v = points; v > 0; --v) (*first)[v] = (*first)[v - 1];
  (*first)[0] = 0;
  return Incidence{*first, *tris};
}

enum class Edge { join, concave, fold };

Edge judge_edge(const Eigen::Vector3d& xa, const Eigen::Vector3d& na, const Eigen::Vector3d& xb,
                const Eigen::Vector3d& nb, double sin_concave, double cos_fold) {
  if (na.squaredNorm() == 0.0 || nb.squaredNorm() == 0.0) return Edge::join;
  if (na.dot(nb) < cos_fold) return Edge::fold;
  // The normal turns by more than the limit and not outwards: concave (also
  // where the turn is mostly across the step, as at a rock's base corner).
  const Eigen::Vector3d turn = na - nb;
  if (turn.squaredNorm() > sin_concave * sin_concave && turn.dot(xa - xb) <= 0.0)
    return Edge::concave;
  return Edge::join;
}

}  // namespace

Status validate(const ClickRegionParams& p) {
  if (!(p.max_concave_step_deg > 0.0 && p.max_concave_step_deg < 90.0))
    return Error::make(Errc::invalid_argument, "click region: max_concave_step_deg not in (0, 90)");
  if (!(p.max_normal_step_deg > 0.0 && p.max_normal_step_deg <= 180.0))
    return Error::make(Errc::invalid_argument, "click region: max_normal_step_deg not in (0, 180]");
  if (!(p.min_share >= 0.0 && p.min_share < 1.0))
    return Error::make(Errc::invalid_argument, "click region: min_share not in [0, 1)");
  if (p.min_points < 3)
    return Error::make(Errc::invalid_argument, "click region: min_points %zu < 3", p.min_points);
  return {};
}

std::size_t click_region_scratch_bytes(std::size_t points, std::size_t triangles) {
  const std::size_t a = alignof(std::uint32_t);
  return (points + 1 + a) * 4 + (3 * triangles + a) * 4 + (points + a) * 4;
}

Result<ClickRegionResult> grow_click_region(std::span<const Eigen::Vector3d> xyz,
                                            std::span<const Eigen::Vector3d> normals,
                                            std::span<const MeshTriangle> mesh, std::size_t seed,
                                            const ClickRegionParams& params,
                                            std::span<PointClass> labels, Arena& arena) {
  PETRA_TRY(validate(params));
  const std::size_t n = xyz.size();
  if (normals.size() != n || labels.size() != n)
    return Error::make(Errc::invalid_argument,
                       "click region: %zu positions, %zu normals, %zu labels differ", n,
                       normals.size(), labels.size());
  if (seed >= n) return Error::make(Errc::out_of_range, "click region: seed %zu of %zu", seed, n);
  for (const MeshTriangle& t : mesh)
    for (int k = 0; k < 3; ++k)
      if (t.v[k] < 0 || static_cast<std::size_t>(t.v[k]) >= n)
        return Error::make(Errc::out_of_range, "click region: mesh vertex %d of %zu", t.v[k], n);
  ArenaScope scope(arena);
  auto inc = build_incidence(n, mesh, arena);
  if (!inc) return inc.error();
  auto queue = arena.allocate_uninitialised<std::uint32_t>(n, "click region: queue");
  if (!queue) return queue.error();
  const double sin_concave = std::sin(params.max_concave_step_deg * kDegToRad);
  const double cos_fold = std::cos(params.max_normal_step_deg * kDegToRad);
  for (PointClass& c : labels) c = PointClass::ground;
  ClickRegionResult out;
  std::size_t head = 0, tail = 0;
  labels[seed] = PointClass::rock;
  (*queue)[tail++] = static_cast<std::uint32_t>(seed);
  while (head < tail) {
    const std::size_t a = (*queue)[head++];
    // A point without a normal joins but is not grown from (the click itself is).
    if (a != seed && normals[a].squaredNorm() == 0.0) continue;
    for (std::uint32_t r = inc->first[a]; r < inc->first[a + 1]; ++r) {
      const MeshTriangle& t = mesh[inc->tris[r]];
      for (int k = 0; k < 3; ++k) {
        const std::size_t b = static_cast<std::size_t>(t.v[k]);
        if (labels[b] == PointClass::rock) continue;
        const Edge e = judge_edge(xyz[a], normals[a], xyz[b], normals[b], sin_concave, cos_fold);
        if (e == Edge::concave) ++out.stopped_concave;
        if (e == Edge::fold) ++out.stopped_fold;
        if (e != Edge::join) continue;
        labels[b] = PointClass::rock;
        (*queue)[tail++] = static_cast<std::uint32_t>(b);
      }
    }
  }
  out.points = tail;
  if (out.points < params.min_points)
    return Error::make(Errc::no_solution,
                       "the rock under the click is too small (%zu points, need %zu): click on "
                       "its largest face",
                       out.points, params.min_points);
  return out;
}

}  // namespace petra
