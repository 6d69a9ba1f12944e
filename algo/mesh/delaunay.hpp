// 2-D Delaunay triangulation (docs/method.md 3d) of the matched points in the
// rectified left image. General input: Bowyer-Watson insertion with ghost
// triangles (a vertex at infinity, so no super-triangle and no large
// coordinates); raster-ordered input: see delaunay_raster.cpp. Incremental path:
//   - exact integer predicates (algo/mesh/predicates.hpp): orient2d, incircle;
//   - points inserted in BRIO rounds, along a Hilbert curve within each round
//     (radix-sorted keys), located by a
//     visibility walk from the last new triangle (bounded; a linear scan is
//     the fallback), cavity grown with an explicit stack;
//   - strict empty-circumcircle criterion: degenerate inputs (grids,
//     cocircular points) get one valid Delaunay triangulation, duplicates are
//     skipped and counted, all-collinear input is an error.
// Inputs: integer points, |x|, |y| <= 2^20. Outputs: triangles (vertex indices
// into the input, positively oriented by orient2d, neighbours across the edge
// opposite each vertex, -1 on the hull) into a caller span of at least
// delaunay_max_triangles(n). Scratch: delaunay_scratch_bytes(n) from the arena,
// released on return. No heap, no recursion.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "algo/core/arena.hpp"
#include "algo/core/result.hpp"
#include "algo/mesh/predicates.hpp"

namespace petra {

struct MeshTriangle {
  std::int32_t v[3] = {-1, -1, -1};  // vertex (point) indices
  std::int32_t n[3] = {-1, -1, -1};  // neighbour across the edge opposite v[i]; -1: none
};

struct DelaunayStats {
  std::size_t triangles = 0;
  std::size_t vertices = 0;    // distinct points used
  std::size_t duplicates = 0;  // points equal to an earlier one (skipped)
  std::size_t hull_edges = 0;
  std::size_t walk_steps = 0;      // total point-location steps (diagnostic)
  std::size_t walk_fallbacks = 0;  // locations that fell back to a linear scan
};

constexpr std::size_t delaunay_max_triangles(std::size_t n) {
  return n < 3 ? 0 : 2 * n;
}
// Enough for either strategy.
std::size_t delaunay_scratch_bytes(std::size_t n);
// The same for points on at most max_rows distinct rows (a disparity map's
// pixels: the ROI's height); the raster path's edge table grows with the rows.
std::size_t delaunay_scratch_bytes(std::size_t n, std::size_t max_rows);

// Raster-ordered input (rows of increasing y, x increasing within a row: the
// order of a disparity map's valid pixels) takes the raster path
// (delaunay_raster.cpp: row strips, hull pockets, Lawson flips; several times
// faster), anything else the incremental one. Both give a Delaunay
// triangulation.
Result<DelaunayStats> delaunay_triangulate(std::span<const IntPoint> points,
                                           std::span<MeshTriangle> triangles, Arena& scratch);

// The strategies themselves (tests compare them).
bool is_raster_ordered(std::span<const IntPoint> points);
Result<DelaunayStats> delaunay_triangulate_incremental(std::span<const IntPoint> points,
                                                       std::span<MeshTriangle> triangles,
                                                       Arena& scratch);
Result<DelaunayStats> delaunay_triangulate_raster(std::span<const IntPoint> points,
                                                  std::span<MeshTriangle> triangles,
                                                  Arena& scratch);
std::size_t delaunay_incremental_scratch_bytes(std::size_t n);
std::size_t delaunay_raster_scratch_bytes(std::size_t n);
std::size_t delaunay_raster_scratch_bytes(std::size_t n, std::size_t max_rows);
// Shared input checks: at least 3 points, coordinates within +-2^20.
Status check_delaunay_input(std::span<const IntPoint> points);

}  // namespace petra
