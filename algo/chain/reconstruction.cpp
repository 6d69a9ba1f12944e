#include "algo/chain/reconstruction.hpp"

#include <algorithm>

#include "algo/core/arena.hpp"
#include "algo/mesh/triangulate.hpp"

namespace petra {

namespace {

constexpr std::size_t kAllocations = 32;

std::size_t roi_px(const ReconstructionBudget& b) {
  return static_cast<std::size_t>(b.max_roi_width) * static_cast<std::size_t>(b.max_roi_height);
}

std::size_t max_triangles(const ReconstructionBudget& b) {
  return delaunay_max_triangles(b.max_points);
}

std::size_t persistent_bytes(const ReconstructionBudget& b) {
  const std::size_t n = b.max_points, t = max_triangles(b);
  const std::size_t roi =
      static_cast<std::size_t>(b.max_roi_width) * static_cast<std::size_t>(b.max_roi_height);
  return arena_bytes_for<std::int16_t>(roi) + 2 * arena_bytes_for<Eigen::Vector3d>(n) +
         arena_bytes_for<PixelPos>(n) + arena_bytes_for<PointClass>(n) +
         arena_bytes_for<std::uint8_t>(n) + arena_bytes_for<MeshTriangle>(t) +
         arena_bytes_for<std::uint8_t>(t);
}

std::size_t transient_bytes(const ReconstructionBudget& b) {
  const std::size_t n = b.max_points, t = max_triangles(b);
  const std::size_t filter = std::max(mean_filter_scratch_bytes(b.max_roi_width),
                                      arena_bytes_for<std::int16_t>(roi_px(b)));
  const std::size_t delaunay =
      arena_bytes_for<IntPoint>(n) +
      delaunay_scratch_bytes(n, static_cast<std::size_t>(b.max_roi_height));
  const std::size_t mesh = mesh_filter_scratch_bytes(t);
  const std::size_t roi =
      static_cast<std::size_t>(b.max_roi_width) * static_cast<std::size_t>(b.max_roi_height);
  const std::size_t normals =
      arena_bytes_for<Eigen::Vector3d>(roi) + surface_normals_scratch_bytes(b.max_roi_width);
  const std::size_t grind = arena_bytes_for<std::uint8_t>(t) + grind_planes_on_mesh_bytes(t);
  const std::size_t region = click_region_scratch_bytes(n, t);
  return std::max(std::max(std::max(filter, delaunay), region),
                  std::max(std::max(mesh, normals), grind));
}

// The clicked point: the cloud point nearest the click within the radius
// that has a surface normal and a mesh triangle (an isolated point grows nothing).
std::size_t clicked_point(const ReconstructionOutput& out, const ClickPx& click, int radius) {
  const std::span<const PixelPos> px = out.pixels;
  std::size_t best = px.size();
  long best_d2 = static_cast<long>(radius) * radius;
  for (std::size_t i = 0; i < px.size(); ++i) {
    const long du = px[i].u - click.u, dv = px[i].v - click.v;
    if (du * du + dv * dv <= best_d2 && out.normals[i].squaredNorm() > 0.0 &&
        out.vertex_class[i] == 1) {
      best = i;
      best_d2 = du * du + dv * dv;
    }
  }
  return best;
}

// A region far smaller than the ROI's surface (a click in a shallow groove,
// whose concave sides ring it): grown again with the concave limit doubled,
// at most twice; the labels and `r` are the last growth's.
Status grow_past_a_groove(const ClickRegionParams& params, std::size_t seed, Arena& arena,
                          ReconstructionOutput& out, ClickRegionResult& r) {
  const double enough = params.min_share * static_cast<double>(out.pixels.size());
  ClickRegionParams loose = params;
  for (int k = 0; k < 2 && static_cast<double>(r.points) < enough; ++k) {
    loose.max_concave_step_deg = std::min(2 * loose.max_concave_step_deg, 89.0);  // valid < 90
    auto again =
        grow_click_region(out.xyz_mm, out.normals, out.mesh, seed, loose, out.point_class, arena);
    if (!again) return again.error();
    r = *again;
    r.loosened = k + 1;
  }
  return {};
}

// From the click: "ground" is the plane of the points around the rock (its
// RMS says how far from a plane); the counts from the labels.
void fit_surroundings(ReconstructionOutput& out) {
  GroundResultT<double>& g = out.ground;
  std::size_t rock = 0;
  for (PointClass c : out.point_class) rock += c == PointClass::rock ? 1 : 0;
  g.rock_points = rock;
  g.ground_points = out.xyz_mm.size() - rock;
  auto f = fit_plane_tls_by<double>(
      out.xyz_mm.size(), [&](std::size_t i) -> const Eigen::Vector3d& { return out.xyz_mm[i]; },
      [&](std::size_t i) { return out.point_class[i] == PointClass::ground; });
  if (f) {
    g.plane = f->plane;
    g.rms_mm = f->rms;
  }
}

// No ground: the rock is the region grown from the click; "ground" becomes
// the plane of the points around it (its RMS says how far from a plane).
Status segment_from_click(const ReconstructionRequest& request, const ReconstructionParams& params,
                          const Error& no_ground, Arena& arena, ReconstructionOutput& out) {
  // Mark the points that some kept triangle uses (vertex_class as scratch; set again later).
  for (std::uint8_t& v : out.vertex_class) v = 0;
  for (const MeshTriangle& t : out.mesh)
    for (int k = 0; k < 3; ++k) out.vertex_class[static_cast<std::size_t>(t.v[k])] = 1;
  // The clicked point, else the next nearest within the radius (up to 8):
  // a point on a small island of the map grows too little.
  std::size_t seed = out.pixels.size();
  Result<ClickRegionResult> r = no_ground;
  for (int attempt = 0; attempt < 8; ++attempt) {
    const std::size_t c = clicked_point(out, request.click, params.ground.click_radius_px);
    if (c == out.pixels.size()) break;
    seed = c;
    out.vertex_class[c] = 2;  // tried
    r = grow_click_region(out.xyz_mm, out.normals, out.mesh, seed, params.click_region,
                          out.point_class, arena);
    if (r || r.code() != Errc::no_solution) break;
  }
  if (seed == out.pixels.size()) return no_ground;  // segment_ground names the click's problem
  if (!r) return r.error();
  PETRA_TRY(grow_past_a_groove(params.click_region, seed, arena, out, *r));
  out.segmentation = SegmentMethod::click_region;
  out.click_region = *r;
  out.ground = {};
  out.ground.click_point = seed;
  fit_surroundings(out);
  return {};
}

// The smallest pixel stride (in both directions, from the ROI's corner) on
// which the map's valid disparities fit `capacity` points.
int point_stride(ImageView<const std::int16_t> q4, std::size_t capacity) {
  for (int s = 1;; ++s) {
    std::size_t count = 0;
    for (int y = 0; y < q4.height(); y += s)
      for (int x = 0; x < q4.width(); x += s) count += is_valid_disparity(q4(x, y)) ? 1 : 0;
    if (count <= capacity) return s;
  }
}

// `map` with the disparities off the stride grid invalid, into `out`.
ConstDisparityMap on_stride(ConstDisparityMap map, int s, std::span<std::int16_t> out) {
  const int w = map.q4.width(), h = map.q4.height();
  ImageView<std::int16_t> v(out.data(), w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      v(x, y) = (x % s == 0 && y % s == 0) ? map.q4(x, y) : kInvalidDisparity;
  return {ImageView<const std::int16_t>(out.data(), w, h), map.roi};
}

}  // namespace

const char* segment_method_name(SegmentMethod m) {
  return m == SegmentMethod::click_region ? "click_region" : "ground_plane";
}

Status validate(const ReconstructionBudget& b) {
  if (b.max_roi_width < 8 || b.max_roi_width > 8192 || b.max_roi_height < 8 ||
      b.max_roi_height > 8192)
    return Error::make(Errc::invalid_argument, "budget: max ROI %dx%d not within 8..8192",
                       b.max_roi_width, b.max_roi_height);
  if (b.max_points < 16 || b.max_points > (std::size_t{1} << 24))
    return Error::make(Errc::invalid_argument, "budget: max_points %zu not within 16..2^24",
                       b.max_points);
  return {};
}

std::size_t reconstruction_arena_bytes(const ReconstructionBudget& b) {
  return persistent_bytes(b) + transient_bytes(b) + kAllocations * kArenaSlackPerAllocation;
}

namespace {

// Disparity range of the input (Table 1).
void disparity_extent(ConstDisparityMap disparity, ReconstructionStats& st) {
  bool any = false;
  for (int y = 0; y < disparity.q4.height(); ++y)
    for (int x = 0; x < disparity.q4.width(); ++x) {
      const std::int16_t q = disparity.q4(x, y);
      if (!is_valid_disparity(q)) continue;
      const double d = disparity_px(q);
      st.disparity_min_px = any ? std::min(st.disparity_min_px, d) : d;
      st.disparity_max_px = any ? std::max(st.disparity_max_px, d) : d;
      any = true;
    }
}

Status mean_filter_step(ConstDisparityMap disparity, const ReconstructionParams& params,
                        Arena& arena, const StepClock& clock, StepTimings& timings,
                        ReconstructionOutput& out) {
  const int w = disparity.q4.width(), h = disparity.q4.height();
  auto filtered = arena.allocate<std::int16_t>(
      static_cast<std::size_t>(w) * static_cast<std::size_t>(h), "filtered disparity");
  if (!filtered) return filtered.error();
  out.filtered = {ImageView<std::int16_t>(filtered->data(), w, h), disparity.roi};
  PETRA_TRY(checkpoint(clock, PipelineStep::mean_filter));
  StepTimer timer(clock, timings, PipelineStep::mean_filter);
  auto f = mean_filter_disparity(disparity, out.filtered, params.filter, arena);
  if (!f) return f.error();
  out.stats.dense_points = f->before;
  out.stats.filtered_points = f->after;
  return ok_status();
}

// Triangulation of the filtered map into at most `n_max` points (eq. 8's
// point, by the rectified pair's closed form: algo/mesh/triangulate).
Status triangulate_step(const RectifiedPair& rect, std::size_t n_max, Arena& arena,
                        const StepClock& clock, StepTimings& timings, ReconstructionOutput& out) {
  ReconstructionStats& st = out.stats;
  auto xyz = arena.allocate<Eigen::Vector3d>(n_max, "cloud positions");
  if (!xyz) return xyz.error();
  auto px = arena.allocate<PixelPos>(n_max, "cloud pixels");
  if (!px) return px.error();
  std::size_t n = 0;
  PETRA_TRY(checkpoint(clock, PipelineStep::triangulate));
  {
    StepTimer timer(clock, timings, PipelineStep::triangulate);
    // Above the points budget: a regular subset of the pixels (the normals
    // and the products keep the whole filtered map).
    ConstDisparityMap input = out.filtered;
    ArenaScope scope(arena);
    st.point_stride = point_stride(input.q4, n_max);
    if (st.point_stride > 1) {
      auto thinned = arena.allocate<std::int16_t>(
          static_cast<std::size_t>(input.q4.width()) * static_cast<std::size_t>(input.q4.height()),
          "disparity on the stride");
      if (!thinned) return thinned.error();
      input = on_stride(input, st.point_stride, *thinned);
    }
    auto t = triangulate_disparity(rect, input, *xyz, *px);
    if (!t) return t.error();
    n = t->points;
    st.triangulated = t->points;
    st.triangulation_rejected = t->rejected;
  }
  out.xyz_mm = xyz->first(n);
  out.pixels = px->first(n);
  if (n < 3)
    return Error::make(Errc::degenerate, "reconstruction: %zu 3-D points, need at least 3", n);
  return ok_status();
}

// Delaunay in the rectified left image, lifted, discontinuities removed.
Status mesh_step(const StereoRig& rig, const ReconstructionParams& params, Arena& arena,
                 const StepClock& clock, StepTimings& timings, ReconstructionOutput& out) {
  ReconstructionStats& st = out.stats;
  const std::size_t n = out.xyz_mm.size();
  auto mesh = arena.allocate<MeshTriangle>(delaunay_max_triangles(n), "mesh");
  if (!mesh) return mesh.error();
  std::size_t nt = 0;
  PETRA_TRY(checkpoint(clock, PipelineStep::delaunay));
  {
    StepTimer timer(clock, timings, PipelineStep::delaunay);
    ArenaScope scope(arena);
    auto ip = arena.allocate<IntPoint>(n, "delaunay points");
    if (!ip) return ip.error();
    for (std::size_t i = 0; i < n; ++i) (*ip)[i] = {out.pixels[i].u, out.pixels[i].v};
    auto d = delaunay_triangulate(*ip, *mesh, arena);
    if (!d) return d.error();
    nt = d->triangles;
    st.delaunay_triangles = d->triangles;
    st.duplicates = d->duplicates;
  }
  PETRA_TRY(checkpoint(clock, PipelineStep::mesh_filter));
  {
    StepTimer timer(clock, timings, PipelineStep::mesh_filter);
    auto f = remove_discontinuities(out.xyz_mm, camera_centre_world(rig.left), params.mesh,
                                    mesh->first(nt), arena);
    if (!f) return f.error();
    st.mesh = *f;
    nt = f->kept;
  }
  out.mesh = mesh->first(nt);
  return ok_status();
}

// Smoothed surface normals per point, from the filtered disparity.
Status normals_step(const RectifiedPair& rect, const ReconstructionParams& params, Arena& arena,
                    const StepClock& clock, StepTimings& timings, ReconstructionOutput& out) {
  const std::size_t n = out.xyz_mm.size();
  const Rect roi = out.filtered.roi;
  const int w = out.filtered.q4.width(), h = out.filtered.q4.height();
  auto normals = arena.allocate<Eigen::Vector3d>(n, "point normals");
  if (!normals) return normals.error();
  out.normals = *normals;
  PETRA_TRY(checkpoint(clock, PipelineStep::normals));
  StepTimer timer(clock, timings, PipelineStep::normals);
  ArenaScope scope(arena);
  // Normals only at the points' pixels (the stride grid), packed.
  const int s = out.stats.point_stride;
  const int packed_w = (w + s - 1) / s, packed_h = (h + s - 1) / s;
  auto grid = arena.allocate<Eigen::Vector3d>(
      static_cast<std::size_t>(packed_w) * static_cast<std::size_t>(packed_h), "pixel normals");
  if (!grid) return grid.error();
  PETRA_TRY(surface_normals(out.filtered, rect.left, params.normals, *grid, arena, s));
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t at = static_cast<std::size_t>((out.pixels[i].v - roi.y) / s) *
                               static_cast<std::size_t>(packed_w) +
                           static_cast<std::size_t>((out.pixels[i].u - roi.x) / s);
    out.normals[i] = (*grid)[at];
  }
  return ok_status();
}

// A fitted ground whose points mostly lean away from it is a rock's faces
// (ground_normals.hpp): no ground, so the rock is grown from the click.
Result<GroundResultT<double>> ground_faces_along_its_plane(const GroundResultT<double>& g,
                                                           const ReconstructionOutput& out,
                                                           const GroundNormalParams& params,
                                                           GroundFailure* why) {
  PETRA_TRY(validate(params));
  const GroundNormalShare s =
      ground_normal_share(out.normals, out.point_class, g.plane.normal, params);
  if (s.share >= params.min_share) return g;
  *why = GroundFailure::no_ground;
  return Error::make(Errc::no_solution,
                     "no ground in the ROI: only %.0f %% of the best plane's points face along "
                     "it (the rock's faces, not ground)",
                     100.0 * s.share);
}

// Rock / ground; from the click where no ground is found.
Status segmentation_step(const StereoRig& rig, const RectifiedPair& rect, Rect roi,
                         const ReconstructionRequest& request, const ReconstructionParams& params,
                         Arena& arena, const StepClock& clock, StepTimings& timings,
                         ReconstructionOutput& out) {
  const std::size_t n = out.xyz_mm.size();
  auto pclass = arena.allocate<PointClass>(n, "point classes");
  if (!pclass) return pclass.error();
  out.point_class = *pclass;
  auto vclass = arena.allocate<std::uint8_t>(n, "vertex classes");
  if (!vclass) return vclass.error();
  out.vertex_class = *vclass;
  PETRA_TRY(checkpoint(clock, PipelineStep::segmentation));
  StepTimer timer(clock, timings, PipelineStep::segmentation);
  GroundFailure why = GroundFailure::none;
  const StereoNoise noise{rect.left.f_px, rect.baseline_mm};
  auto g = segment_ground<double>(out.xyz_mm, out.pixels, roi, request.click,
                                  camera_centre_world(rig.left), params.ground, out.point_class,
                                  noise, &why);
  if (g) g = ground_faces_along_its_plane(*g, out, params.ground_normals, &why);
  if (g) {
    out.ground = *g;
  } else if (why != GroundFailure::no_ground) {
    return g.error();
  } else if (!request.click.present) {
    return Error::make(g.code(), "%s; click on the rock", g.error().message);
  } else {
    PETRA_TRY(segment_from_click(request, params, g.error(), arena, out));
  }
  return ok_status();
}

// A triangle with three rock vertices.
bool rock_triangle(const ReconstructionOutput& out, std::size_t i) {
  for (int k = 0; k < 3; ++k)
    if (out.point_class[static_cast<std::size_t>(out.mesh[i].v[k])] != PointClass::rock)
      return false;
  return true;
}

// Grind planes on the rock triangles into out.planes; plane_of out: each
// triangle's plane (0..count-1 in rank order, 0xFF none).
Status grind_rock_triangles(const StereoRig& rig, const RectifiedPair& rect,
                            const ReconstructionRequest& request,
                            const ReconstructionParams& params, Arena& arena,
                            std::span<std::uint8_t> plane_of, ReconstructionOutput& out) {
  std::size_t nr = 0;
  for (std::size_t i = 0; i < out.mesh.size(); ++i) {
    const bool r = rock_triangle(out, i);
    plane_of[i] = r ? 1 : 0;
    nr += r ? 1 : 0;
  }
  out.stats.rock_triangles = nr;
  auto g =
      grind_planes_on_mesh(rig, rect, out, request.planes, params, arena, plane_of, request.reach);
  if (!g) return g.error();
  out.planes = *g;
  return ok_status();
}

// A rock grown from the click may have run onto the surface it stands on
// (support_surface.hpp): whether an accepted plane lies there (into as_support).
bool support_plane(const ReconstructionOutput& out, const SupportParams& params,
                   SupportPlane& as_support) {
  for (int k = 0; k < out.planes.accepted; ++k) {
    const GrindPlane& g = out.planes.planes[k];
    as_support = {g.face_normal, g.face_centroid_mm, g.area_mm2, g.rms_mm};
    const RockInFront f =
        rock_in_front(out.xyz_mm, out.point_class, out.ground.click_point, as_support, params);
    if (stands_on(f, params)) return true;
  }
  return false;
}

// Grind planes on the rock triangles; mesh and vertex classes from them.
// From the click: planes on the support dropped with its points, found again.
Status grind_planes_step(const StereoRig& rig, const RectifiedPair& rect,
                         const ReconstructionRequest& request, const ReconstructionParams& params,
                         Arena& arena, const StepClock& clock, StepTimings& timings,
                         ReconstructionOutput& out) {
  const std::size_t n = out.xyz_mm.size(), nt = out.mesh.size();
  auto mclass = arena.allocate<std::uint8_t>(nt, "mesh classes");
  if (!mclass) return mclass.error();
  out.mesh_class = *mclass;
  PETRA_TRY(validate(params.support));
  PETRA_TRY(checkpoint(clock, PipelineStep::grind_planes));
  StepTimer timer(clock, timings, PipelineStep::grind_planes);
  ArenaScope scope(arena);
  auto plane_of = arena.allocate<std::uint8_t>(nt, "mesh triangle planes");
  if (!plane_of) return plane_of.error();
  PETRA_TRY(grind_rock_triangles(rig, rect, request, params, arena, *plane_of, out));
  SupportPlane s;
  while (out.segmentation == SegmentMethod::click_region && out.support_planes < kMaxClasses &&
         support_plane(out, params.support, s)) {
    ++out.support_planes;
    out.support_points += drop_support(out.xyz_mm, out.point_class, s, params.support);
    fit_surroundings(out);
    PETRA_TRY(grind_rock_triangles(rig, rect, request, params, arena, *plane_of, out));
  }
  for (std::size_t i = 0; i < n; ++i)
    out.vertex_class[i] = out.point_class[i] == PointClass::rock ? kVertexRock : kVertexGround;
  for (std::size_t i = 0; i < nt; ++i) {
    out.mesh_class[i] = rock_triangle(out, i) ? kVertexRock : kVertexGround;
    const std::uint8_t p = (*plane_of)[i];
    if (p == 0xFF) continue;
    const std::uint8_t cls = static_cast<std::uint8_t>(kVertexPlane0 + p);
    out.mesh_class[i] = cls;
    for (int k = 0; k < 3; ++k) out.vertex_class[static_cast<std::size_t>(out.mesh[i].v[k])] = cls;
  }
  return ok_status();
}

// Spreads the plane index of subset triangle j (plane[j]) to its mesh index
// origin[j] >= j, in place from the back; 0xFF where no subset triangle is.
void spread_to_mesh(std::span<const std::int32_t> origin, std::span<std::uint8_t> plane) {
  std::size_t next = plane.size();  // plane[next..] hold their final value
  for (std::size_t j = origin.size(); j-- > 0;) {
    const std::size_t o = static_cast<std::size_t>(origin[j]);
    const std::uint8_t p = plane[j];
    for (std::size_t i = o + 1; i < next; ++i) plane[i] = 0xFF;
    plane[o] = p;
    next = o;
  }
  for (std::size_t i = 0; i < next; ++i) plane[i] = 0xFF;
}

}  // namespace

std::size_t grind_planes_on_mesh_bytes(std::size_t triangles) {
  return arena_bytes_for<MeshTriangle>(triangles) + arena_bytes_for<std::int32_t>(triangles) +
         std::max(mesh_filter_scratch_bytes(triangles), grind_planes_scratch_bytes(triangles));
}

Result<GrindResult> grind_planes_on_mesh(const StereoRig& rig, const RectifiedPair& rect,
                                         const ReconstructionOutput& out, int c,
                                         const ReconstructionParams& params, Arena& arena,
                                         std::span<std::uint8_t> triangle_plane,
                                         const DiscReach* reach) {
  const std::size_t nt = out.mesh.size();
  if (triangle_plane.size() != nt)
    return Error::make(Errc::invalid_argument,
                       "grind planes on the mesh: %zu triangle marks for %zu triangles",
                       triangle_plane.size(), nt);
  ArenaScope scope(arena);
  auto subset = arena.allocate<MeshTriangle>(nt, "taken triangles");
  if (!subset) return subset.error();
  auto origin = arena.allocate<std::int32_t>(nt, "taken triangle origins");
  if (!origin) return origin.error();
  std::size_t nr = 0;
  for (std::size_t i = 0; i < nt; ++i) {
    (*subset)[i] = out.mesh[i];
    if (triangle_plane[i] != 0) (*origin)[nr++] = static_cast<std::int32_t>(i);
  }
  auto kept = keep_triangles(
      subset->first(nt), [&](std::size_t i) { return triangle_plane[i] != 0; }, arena);
  if (!kept) return kept.error();
  PETRA_ASSERT(*kept == nr);
  auto g = find_grind_planes(
      out.xyz_mm, subset->first(nr), camera_centre_world(rig.left), c, params.grind, arena,
      triangle_plane.first(nr), out.normals,
      RigGeometry{rect.left.f_px, rect.baseline_mm, static_cast<double>(params.filter.window)},
      reach);
  if (!g) return g.error();
  spread_to_mesh(origin->first(nr), triangle_plane);
  return *g;
}

Result<ReconstructionOutput> reconstruct(const StereoRig& rig, const RectifiedPair& rect,
                                         ConstDisparityMap disparity,
                                         const ReconstructionRequest& request,
                                         const ReconstructionParams& params,
                                         const ReconstructionBudget& budget, Arena& arena,
                                         const StepClock& clock, StepTimings& timings) {
  PETRA_TRY(validate(budget));
  const int w = disparity.q4.width(), h = disparity.q4.height();
  if (w > budget.max_roi_width || h > budget.max_roi_height)
    return Error::make(Errc::capacity_exceeded,
                       "reconstruction: ROI %dx%d exceeds the budget %dx%d", w, h,
                       budget.max_roi_width, budget.max_roi_height);
  if (request.planes < 1 || request.planes > kMaxClasses)
    return Error::make(Errc::out_of_range, "reconstruction: c = %d planes, must be 1..%d",
                       request.planes, kMaxClasses);
  ReconstructionOutput out;
  disparity_extent(disparity, out.stats);
  PETRA_TRY(mean_filter_step(disparity, params, arena, clock, timings, out));
  PETRA_TRY(triangulate_step(rect, budget.max_points, arena, clock, timings, out));
  PETRA_TRY(mesh_step(rig, params, arena, clock, timings, out));
  PETRA_TRY(normals_step(rect, params, arena, clock, timings, out));
  PETRA_TRY(
      segmentation_step(rig, rect, disparity.roi, request, params, arena, clock, timings, out));
  PETRA_TRY(grind_planes_step(rig, rect, request, params, arena, clock, timings, out));
  return out;
}

}  // namespace petra
