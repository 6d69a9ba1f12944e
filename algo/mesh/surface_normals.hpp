// Surface normals from the disparity map, for clustering faces. A plane in
// the rectified camera frame has a disparity linear in the pixel position:
//   n . X = rho  =>  d(u, v) = (B/rho) (n_x (u-cx) + n_y (v-cy) + n_z f),
// so a least-squares fit d = a u + b v + c over a window x window box of
// valid pixels gives the normal n ~ (a, b, (c + a cx + b cy) / f) (rectified
// camera frame, then rotated to the world). A single mesh triangle's normal
// (AB x AC) at 0.9 mm pixel spacing and 0.5 mm depth noise scatters by tens
// of degrees; the fitted normal over 9 x 9 px scatters by about one.
// Sliding column sums (as the mean filter): O(width) scratch, O(1) per pixel.
// Inputs: a disparity map (Q4), the rectified left camera, the baseline-free
// geometry needs only f, cx, cy, R. Output: one normal per pixel of the map
// into a caller buffer (unit, oriented towards the camera; zero where fewer
// than min_valid pixels of the box are valid or the fit is degenerate).
// Scratch: surface_normals_scratch_bytes(width) from the arena. No heap.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <span>

#include "algo/camera/rectify_geometry.hpp"
#include "algo/core/arena.hpp"
#include "algo/core/disparity.hpp"
#include "algo/core/result.hpp"

namespace petra {

struct NormalParams {
  int window = 9;          // odd, 3..31 px
  double min_valid = 0.5;  // share of the box that must be valid
};

Status validate(const NormalParams& p);
std::size_t surface_normals_scratch_bytes(int width);

// normals[y * width + x] for map pixel (x, y). With stride s > 1 only the
// pixels whose x and y are multiples of s (the reconstruction's points on a
// pixel stride) get a normal, each the same as with stride 1, packed as
// normals[(y / s) * ceil(width / s) + x / s]; the sums still slide over
// every pixel, so the work left is the column sums.
Status surface_normals(ConstDisparityMap map, const RectifiedCamera& camera,
                       const NormalParams& params, std::span<Eigen::Vector3d> normals,
                       Arena& scratch, int stride = 1);

}  // namespace petra
