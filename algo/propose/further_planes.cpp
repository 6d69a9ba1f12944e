#include "algo/propose/further_planes.hpp"

#include <cmath>

namespace petra {

std::uint8_t RockOnMap::at(double u, double v) const {
  if (map_width <= 0 || cell_px <= 0 || !(u >= 0.0) || !(v >= 0.0)) return kNoRock;
  const long x = std::lround(u) / cell_px, y = std::lround(v) / cell_px;
  const long h = static_cast<long>(map.size()) / map_width;
  if (x >= map_width || y >= h) return kNoRock;
  return map[static_cast<std::size_t>(y * map_width + x)];
}

bool RockOnMap::holds(const ReconstructionOutput& r, const MeshTriangle& t) const {
  double u = 0, v = 0;
  for (int k = 0; k < 3; ++k) {
    const PixelPos& p = r.pixels[static_cast<std::size_t>(t.v[k])];
    u += p.u;
    v += p.v;
  }
  return at(u / 3.0, v / 3.0) == index;
}

void planes_mostly_on(const ReconstructionOutput& r, const RockOnMap& rock,
                      bool (&on)[kMaxClasses]) {
  long own[kMaxClasses] = {}, all[kMaxClasses] = {};
  for (std::size_t i = 0; i < r.pixels.size(); ++i) {
    const int k = r.vertex_class[i] - kVertexPlane0;
    if (k < 0 || k >= kMaxClasses) continue;
    ++all[k];
    if (rock.at(r.pixels[i].u, r.pixels[i].v) == rock.index) ++own[k];
  }
  for (int k = 0; k < kMaxClasses; ++k) on[k] = 2 * own[k] > all[k];
}

Result<GrindResult> further_planes(const StereoRig& rig, const RectifiedPair& rect,
                                   const ReconstructionParams& params,
                                   const ReconstructionOutput& r, const RockOnMap& rock,
                                   const bool (&explained)[kMaxClasses], int c,
                                   const DiscReach* reach, Arena& arena) {
  const std::size_t nt = r.mesh.size();
  if (r.mesh_class.size() != nt)
    return Error::make(Errc::invalid_argument, "further planes: %zu mesh classes, %zu triangles",
                       r.mesh_class.size(), nt);
  ArenaScope scope(arena);
  auto taken = arena.allocate<std::uint8_t>(nt, "further planes' triangles");
  if (!taken) return taken.error();
  std::size_t left = 0;
  for (std::size_t i = 0; i < nt; ++i) {
    const int cls = r.mesh_class[i];
    const int k = cls - kVertexPlane0;
    const bool free = cls == kVertexRock || (k >= 0 && k < kMaxClasses && !explained[k]);
    (*taken)[i] = free && rock.holds(r, r.mesh[i]) ? 1 : 0;
    left += (*taken)[i];
  }
  if (left < 3 * static_cast<std::size_t>(c)) return GrindResult{};  // too few for c: none
  return grind_planes_on_mesh(rig, rect, r, c, params, arena, *taken, reach);
}

bool same_face(const GrindPlane& a, const GrindPlane& b, const GrindParams& p) {
  return same_plane(a.normal, a.centroid_mm, b.normal, b.centroid_mm, p);
}

}  // namespace petra
