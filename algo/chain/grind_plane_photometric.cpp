#include "algo/chain/grind_plane_photometric.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstddef>

#include "algo/surface/grind_planes.hpp"

namespace petra {

namespace {

constexpr std::uint8_t kUnknown = 0xFF;
constexpr double kSpanMm = 10.0;  // in-plane offsets that fix the disparity plane
constexpr double kSpanPx = 10.0;  // pixel offsets that fix the 3-D plane

// The rectified disparity plane of a 3-D plane, centred on the centroid's pixel.
Result<DisparityPlane> to_disparity_plane(const RectifiedPair& rect, const Eigen::Vector3d& n,
                                          const Eigen::Vector3d& centroid) {
  const Eigen::Vector3d e1 = n.unitOrthogonal();
  const Eigen::Vector3d e2 = n.cross(e1);
  auto p0 = rectified_project(rect, centroid);
  if (!p0) return p0.error();
  auto p1 = rectified_project(rect, centroid + kSpanMm * e1);
  if (!p1) return p1.error();
  auto p2 = rectified_project(rect, centroid + kSpanMm * e2);
  if (!p2) return p2.error();
  // d - d0 = a (u - u0) + b (v - v0) through the other two points.
  Eigen::Matrix2d A;
  A << p1->uv_left.x() - p0->uv_left.x(), p1->uv_left.y() - p0->uv_left.y(),
      p2->uv_left.x() - p0->uv_left.x(), p2->uv_left.y() - p0->uv_left.y();
  const Eigen::Vector2d rhs(p1->disparity - p0->disparity, p2->disparity - p0->disparity);
  if (std::abs(A.determinant()) < 1e-9)
    return Error::make(Errc::no_solution, "photometric plane: plane seen edge-on");
  const Eigen::Vector2d ab = A.partialPivLu().solve(rhs);
  return DisparityPlane{ab(0), ab(1), p0->disparity, p0->uv_left.x(), p0->uv_left.y()};
}

// Unit normal of a disparity plane in the world (sign arbitrary).
Result<Eigen::Vector3d> world_normal(const RectifiedPair& rect, const DisparityPlane& q) {
  const double u = q.u0, v = q.v0;
  auto a = rectified_point(rect, u, v, q.at(u, v));
  if (!a) return a.error();
  auto b = rectified_point(rect, u + kSpanPx, v, q.at(u + kSpanPx, v));
  if (!b) return b.error();
  auto c = rectified_point(rect, u, v + kSpanPx, q.at(u, v + kSpanPx));
  if (!c) return c.error();
  const Eigen::Vector3d n = (*b - *a).cross(*c - *a);
  if (!(n.norm() > 0)) return Error::make(Errc::no_solution, "photometric plane: degenerate");
  return n.normalized();
}

}  // namespace

std::size_t grind_photometric_scratch_bytes(int roi_width, int roi_height) {
  const std::size_t area =
      static_cast<std::size_t>(roi_width) * static_cast<std::size_t>(roi_height);
  return area * (1 + sizeof(PixelPos)) +
         face_pixels_scratch(roi_width, roi_height) * sizeof(std::int32_t) +
         3 * alignof(std::max_align_t);
}

Result<int> refine_grind_planes_photometric(const RectifiedPair& rect, ConstGray8View left,
                                            ConstGray8View right, Rect right_valid,
                                            const PhotometricPlaneParams& params,
                                            ReconstructionOutput& out, Arena& arena,
                                            std::span<PlaneMove> moves) {
  PETRA_TRY(validate(params));
  if (!params.enabled || out.planes.count == 0) return 0;
  const Rect roi = out.filtered.roi;
  const std::size_t area = static_cast<std::size_t>(roi.w) * static_cast<std::size_t>(roi.h);
  ArenaScope scope(arena);
  auto cls = arena.allocate<std::uint8_t>(area, "photometric class image");
  if (!cls) return cls.error();
  auto pix = arena.allocate<PixelPos>(area, "photometric face pixels");
  if (!pix) return pix.error();
  auto spans =
      arena.allocate<std::int32_t>(face_pixels_scratch(roi.w, roi.h), "photometric face spans");
  if (!spans) return spans.error();
  for (std::uint8_t& c : *cls) c = kUnknown;
  for (std::size_t i = 0; i < out.pixels.size(); ++i) {
    const int x = out.pixels[i].u - roi.x, y = out.pixels[i].v - roi.y;
    if (x < 0 || y < 0 || x >= roi.w || y >= roi.h) continue;
    (*cls)[static_cast<std::size_t>(y) * static_cast<std::size_t>(roi.w) +
           static_cast<std::size_t>(x)] = out.vertex_class[i];
  }
  const ImageView<const std::uint8_t> classes(cls->data(), roi.w, roi.h);
  const Eigen::Vector3d camera = -rect.left.R.transpose() * rect.left.T_mm;
  int refined = 0;
  for (int k = 0; k < out.planes.count; ++k) {
    GrindPlane& plane = out.planes.planes[k];
    // A footprint's own plane (the face curves): the whole face's gray
    // levels would turn it towards the face's mean plane.
    if (plane.footprint_local) continue;
    std::size_t n = face_pixels(classes, roi, static_cast<std::uint8_t>(kVertexPlane0 + k),
                                params.edge_px, *spans, *pix);
    // An even sample of a large face: the plane is fixed long before, and
    // the time stays bounded whatever the ROI.
    const std::size_t cap = static_cast<std::size_t>(params.max_pixels);
    if (n > cap) {
      for (std::size_t i = 0; i < cap; ++i) (*pix)[i] = (*pix)[i * n / cap];
      n = cap;
    }
    // The face's plane under the grind point (which stands off it on a
    // curved face): the refinement moves that plane, the point moves with it.
    const Eigen::Vector3d on_face =
        plane.centroid_mm -
        plane.normal.dot(plane.centroid_mm - plane.face_centroid_mm) * plane.normal;
    auto initial = to_disparity_plane(rect, plane.normal, on_face);
    if (!initial) continue;  // seen edge-on: nothing to refine
    auto fit = refine_plane_photometric(left, right, right_valid, pix->first(n), *initial, params);
    if (!fit) return fit.error();
    if (!fit->accepted) continue;
    auto n0 = world_normal(rect, *initial);
    auto n1 = world_normal(rect, fit->plane);
    if (!n0 || !n1) continue;
    if (n1->dot(*n0) < 0) *n1 = -*n1;
    // The refinement's rotation applied to the mesh's normal: what the
    // rectified geometry and the eq. 8 triangulation share cancels.
    const Eigen::Quaterniond turn = Eigen::Quaterniond::FromTwoVectors(*n0, *n1);
    const double c = initial->c;
    auto before = rectified_point(rect, initial->u0, initial->v0, c);
    auto after =
        rectified_point(rect, initial->u0, initial->v0, fit->plane.at(initial->u0, initial->v0));
    if (!before || !after) continue;
    if (static_cast<std::size_t>(k) < moves.size())
      moves[static_cast<std::size_t>(k)] = PlaneMove{true, plane.normal, *before, *after};
    plane.normal = (turn * plane.normal).normalized();
    plane.face_normal = plane.normal;  // the face's plane is the one refined
    plane.centroid_mm += *after - *before;
    plane.view_angle_deg = plane_view_angle_deg(plane.normal, plane.centroid_mm, camera);
    if (k < out.planes.accepted) ++refined;
  }
  return refined;
}

}  // namespace petra
