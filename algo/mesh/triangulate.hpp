// Triangulation by the paper's least-squares system (docs/method.md 3c, eq. 4-8).
// Each Tsai camera (with its radial distortion) gives two linear equations in
// the world point Pw from its pixel (u, v):
//   A = Xu = (1 + k1 r^2) Xd,  Xd = (u - cx) dx / sx     (undistorted sensor x, mm)
//   B = Yu = (1 + k1 r^2) Yd,  Yd = (v - cy) dy,  r^2 = Xd^2 + Yd^2
//   (A r3 - f r1) . Pw = f tx - A tz      (r_i: rows of R)
//   (B r3 - f r2) . Pw = f ty - B tz
// Stacked for both cameras as the 4x3 system (8) and solved by least squares
// through its 3x3 normal equations (LDL^T). World frame of calib.json, mm.
// (The paper prints du(u-u0) for A only and dv(v-v0) for C: a typo; C is the
// right camera's Xu.) Written over a scalar type S so it also runs in Q format.
//
// triangulate_disparity: every valid pixel of a rectified disparity map is a
// correspondence rectified left (u, v) <-> right (u - d, v). Its two rays meet
// exactly, so the point is the rectified pair's closed form (rectified_point:
// Z = f B / d, rotated into the world): the point eq. 8 gives from the same
// correspondence mapped back to original pixels (within 1e-6 mm, the lens
// distortion's round trip; test_triangulate) at a twentieth of the cost.
// Inputs: the rectified geometry, the map; outputs: positions and pixels
// into caller spans (capacity = point budget). No heap, no scratch.
#pragma once

#include <cstddef>
#include <span>

#include "algo/camera/camera_model.hpp"
#include "algo/camera/rectify_geometry.hpp"
#include "algo/core/disparity.hpp"
#include "algo/core/result.hpp"
#include "algo/mesh/cloud.hpp"
#include "algo/mesh/linalg3.hpp"

namespace petra {

// A Tsai camera's parameters in scalar type S (eq. 4-7 use nothing else).
// The pixel pitch is held as pixels per mm (sx/dx, 1/dy): Xd = (u - cx) dx/sx
// becomes a division by a number near 200, which a Q format holds to 1e-7,
// where dx = 0.00465 mm itself would lose 1e-3 in Q47.16.
template <class S>
struct Eq8Camera {
  S f_mm{}, kappa1{}, cx_px{}, cy_px{}, px_per_mm_x{}, px_per_mm_y{};
  Mat3T<S> R = Mat3T<S>::Identity();
  Vec3T<S> T_mm = Vec3T<S>::Zero();
};

template <class S>
Eq8Camera<S> eq8_camera(const TsaiCamera& c) {
  Eq8Camera<S> e;
  e.f_mm = S(c.f_mm);
  e.kappa1 = S(c.kappa1);
  e.cx_px = S(c.cx_px);
  e.cy_px = S(c.cy_px);
  e.px_per_mm_x = S(c.sx / c.dx_mm);
  e.px_per_mm_y = S(1.0 / c.dy_mm);
  for (int i = 0; i < 3; ++i) {
    e.T_mm(i) = S(c.T_mm(i));
    for (int j = 0; j < 3; ++j) e.R(i, j) = S(c.R(i, j));
  }
  return e;
}

// Adds one camera's two rows of eq. 8 to the normal equations M x = b.
template <class S>
void add_eq8_rows(const Eq8Camera<S>& c, const Vec2T<S>& uv, Mat3T<S>& m, Vec3T<S>& b) {
  const S xd = (uv(0) - c.cx_px) / c.px_per_mm_x;
  const S yd = (uv(1) - c.cy_px) / c.px_per_mm_y;
  const S radial = S(1) + c.kappa1 * (xd * xd + yd * yd);
  const S xu = radial * xd;  // A (left) or C (right)
  const S yu = radial * yd;  // B (left) or D (right)
  const Vec3T<S> r1 = c.R.row(0).transpose(), r2 = c.R.row(1).transpose(),
                 r3 = c.R.row(2).transpose();
  const Vec3T<S> row_x = xu * r3 - c.f_mm * r1;
  const Vec3T<S> row_y = yu * r3 - c.f_mm * r2;
  const S rhs_x = c.f_mm * c.T_mm(0) - xu * c.T_mm(2);
  const S rhs_y = c.f_mm * c.T_mm(1) - yu * c.T_mm(2);
  m += row_x * row_x.transpose() + row_y * row_y.transpose();
  b += row_x * rhs_x + row_y * rhs_y;
}

// World point (mm) of the correspondence left (u, v) <-> right (u, v), both in
// ORIGINAL pixel coordinates. Fails (degenerate) when the rays are parallel.
template <class S>
Result<Vec3T<S>> triangulate_eq8(const Eq8Camera<S>& left, const Eq8Camera<S>& right,
                                 const Vec2T<S>& uv_left, const Vec2T<S>& uv_right) {
  Mat3T<S> m = Mat3T<S>::Zero();
  Vec3T<S> b = Vec3T<S>::Zero();
  add_eq8_rows(left, uv_left, m, b);
  add_eq8_rows(right, uv_right, m, b);
  const Ldlt3<S> f = ldlt3<S>(m);
  // The last pivot measures the depth constraint; ~0 for parallel rays.
  if (!f.positive || !(f.d2 > f.d0 * S(1e-12)))
    return Error::make(Errc::degenerate, "triangulate: rays are parallel (no intersection)");
  return f.solve(b);
}

struct TriangulationStats {
  std::size_t points = 0;    // written to the output
  std::size_t rejected = 0;  // valid disparities that gave no point (see header)
};

// Rejected (counted, not written): d <= 0 (at or beyond infinity). The output spans must hold every
// valid pixel of the map; otherwise capacity_exceeded names the budget. `factor` > 1: the map was
// matched on the pair box-downsampled by it (algo/stereo/downsample): pixel x stands for the
// rectified pixels x f .. x f + f - 1 (centre x f + (f - 1) / 2) and its disparity is d f; `pixels`
// stay in the map's own (downsampled) coordinates.
Result<TriangulationStats> triangulate_disparity(const RectifiedPair& rect,
                                                 ConstDisparityMap disparity,
                                                 std::span<Eigen::Vector3d> xyz_mm,
                                                 std::span<PixelPos> pixels, int factor = 1);

}  // namespace petra
