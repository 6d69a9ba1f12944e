#include "algo/propose/rock_detection.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "algo/camera/camera_model.hpp"
#include "algo/core/arena.hpp"
#include "algo/mesh/triangulate.hpp"
#include "algo/propose/rock_split.hpp"
#include "algo/stereo/downsample.hpp"

namespace petra {

namespace {

constexpr std::size_t kAllocations = 18;  // each padded to its alignment
constexpr std::int32_t kNone = -1;

// The downsampled grid: the whole image / factor (a partial block dropped).
struct Grid {
  int w = 0, h = 0;
  std::size_t px() const { return static_cast<std::size_t>(w) * static_cast<std::size_t>(h); }
};

Grid grid_of(const DetectionBudget& b) {
  return {b.image_width / b.factor, b.image_height / b.factor};
}

MatchDpParams coarse_match(const DetectionBudget& b, const DetectionParams& p) {
  MatchDpParams m = p.match;
  m.disp_min = b.search_min_px / b.factor;
  m.disp_max = (b.search_max_px + b.factor - 1) / b.factor;
  return m;
}

MatchBudget match_budget(const DetectionBudget& b) {
  const Grid g = grid_of(b);
  const MatchDpParams m = coarse_match(b, DetectionParams{});
  return {g.w, g.h, m.disp_max - m.disp_min + 1};
}

// Kept from the match on: the points and what is computed on them.
std::size_t point_bytes(const Grid& g) {
  const std::size_t n = g.px();
  return 2 * arena_bytes_for<Eigen::Vector3d>(n) + arena_bytes_for<PixelPos>(n) +
         arena_bytes_for<PointClass>(n) +
         4 * arena_bytes_for<std::int32_t>(n) +  // grid index, region ids, flood stack, parts
         arena_bytes_for<float>(n);              // heights above the ground, for the split
}

}  // namespace

Status validate(const DetectionBudget& b) {
  if (b.factor < 1 || b.factor > 8)
    return Error::make(Errc::invalid_argument, "detection: factor %d not within 1..8", b.factor);
  if (b.image_width < 16 * b.factor || b.image_height < 16 * b.factor ||
      b.image_width > kRemapMaxSide || b.image_height > kRemapMaxSide)
    return Error::make(Errc::invalid_argument,
                       "detection: image %dx%d not within 16 x factor..%d px", b.image_width,
                       b.image_height, kRemapMaxSide);
  if (b.search_min_px < 0 || b.search_max_px <= b.search_min_px)
    return Error::make(Errc::invalid_argument, "detection: envelope %d..%d px is empty",
                       b.search_min_px, b.search_max_px);
  return {};
}

Status validate(const DetectionParams& p) {
  PETRA_TRY(validate(p.ground));
  PETRA_TRY(validate(p.ground_normals));
  if (!(p.band_rms >= 0) || !(p.min_band_mm >= 0) || !(p.band_sigmas >= 0) ||
      !(p.max_range_mm > 0) || !(p.min_height_mm >= 0) || !(p.min_size_mm >= 0) ||
      p.min_pixels < 1 || !(p.pad >= 0) || p.min_pad_px < 0 || !(p.split_prominence_mm >= 0))
    return Error::make(Errc::invalid_argument,
                       "detection: band, height, size, pixels and padding must be >= 0 "
                       "(min_pixels >= 1)");
  return {};
}

RockMapShape rock_map_shape(const DetectionBudget& b) {
  const Grid g = grid_of(b);
  const int step = std::max({1, (g.w + kRockMapMaxWidth - 1) / kRockMapMaxWidth,
                             (g.h + kRockMapMaxHeight - 1) / kRockMapMaxHeight});
  return {(g.w + step - 1) / step, (g.h + step - 1) / step, step};
}

std::size_t detection_arena_bytes(const DetectionBudget& b) {
  const Grid g = grid_of(b);
  const std::size_t image =
      static_cast<std::size_t>(b.image_width) * static_cast<std::size_t>(b.image_height);
  const std::size_t kept = 2 * arena_bytes_for<std::uint8_t>(image) +
                           2 * arena_bytes_for<std::uint8_t>(g.px()) +
                           arena_bytes_for<std::int16_t>(g.px());
  return kept + std::max(match_dp_scratch_bytes(match_budget(b)), point_bytes(g)) +
         kAllocations * kArenaSlackPerAllocation;
}

namespace {

struct Views {
  Gray8View left, right;  // downsampled, whole grid
  DisparityMap disparity;
};

// Rectifies the whole pair and downsamples it onto the grid.
Result<Views> coarse_pair(const Rectifier& rectifier, ConstGray8View left, ConstGray8View right,
                          Rect region, const DetectionBudget& b, Arena& arena) {
  const std::size_t image =
      static_cast<std::size_t>(b.image_width) * static_cast<std::size_t>(b.image_height);
  const Grid g = grid_of(b);
  auto rl = arena.allocate<std::uint8_t>(image, "detection: rectified left");
  if (!rl) return rl.error();
  auto rr = arena.allocate<std::uint8_t>(image, "detection: rectified right");
  if (!rr) return rr.error();
  auto cl = arena.allocate<std::uint8_t>(g.px(), "detection: coarse left");
  if (!cl) return cl.error();
  auto cr = arena.allocate<std::uint8_t>(g.px(), "detection: coarse right");
  if (!cr) return cr.error();
  auto q4 = arena.allocate<std::int16_t>(
      static_cast<std::size_t>(region.w) * static_cast<std::size_t>(region.h),
      "detection: disparity");
  if (!q4) return q4.error();
  const Gray8View full_l(rl->data(), b.image_width, b.image_height);
  const Gray8View full_r(rr->data(), b.image_width, b.image_height);
  PETRA_TRY(rectifier.rectify(StereoSide::left, left, full_l));
  PETRA_TRY(rectifier.rectify(StereoSide::right, right, full_r));
  Views v{Gray8View(cl->data(), g.w, g.h), Gray8View(cr->data(), g.w, g.h),
          DisparityMap{ImageView<std::int16_t>(q4->data(), region.w, region.h), region}};
  const Rect whole{0, 0, g.w * b.factor, g.h * b.factor};
  PETRA_TRY(downsample_box(full_l, whole, b.factor, v.left));
  PETRA_TRY(downsample_box(full_r, whole, b.factor, v.right));
  return v;
}

// The request's region (original left px; empty: all) on the grid.
Result<Rect> coarse_region(const Rectifier& rectifier, Rect region, const DetectionBudget& b) {
  const Grid g = grid_of(b);
  if (region.empty()) return Rect{0, 0, g.w, g.h};
  auto r = rectifier.roi_to_rectified(StereoSide::left, region);
  if (!r) return r.error();
  const int x0 = std::max(0, r->x / b.factor), y0 = std::max(0, r->y / b.factor);
  const int x1 = std::min(g.w, (r->x + r->w + b.factor - 1) / b.factor);
  const int y1 = std::min(g.h, (r->y + r->h + b.factor - 1) / b.factor);
  if (x1 - x0 < 16 || y1 - y0 < 16)
    return Error::make(Errc::out_of_range,
                       "detection: region (%d,%d %dx%d) is under 16 x 16 px at 1/%d resolution",
                       region.x, region.y, region.w, region.h, b.factor);
  return Rect{x0, y0, x1 - x0, y1 - y0};
}

// The cloud on the grid: positions, grid pixels and, per grid pixel, the
// point's index (kNone where no point).
struct GridCloud {
  std::span<Eigen::Vector3d> xyz;
  std::span<PixelPos> pixels;
  std::span<std::int32_t> index;  // grid w x h
  int w = 0, h = 0;
  std::int32_t at(int x, int y) const {
    return index[static_cast<std::size_t>(y) * static_cast<std::size_t>(w) +
                 static_cast<std::size_t>(x)];
  }
};

Result<GridCloud> grid_cloud(const Rectifier& rectifier, ConstDisparityMap disparity,
                             const DetectionBudget& b, Arena& arena) {
  const Grid g = grid_of(b);
  auto xyz = arena.allocate<Eigen::Vector3d>(g.px(), "detection: points");
  if (!xyz) return xyz.error();
  auto px = arena.allocate<PixelPos>(g.px(), "detection: point pixels");
  if (!px) return px.error();
  auto index = arena.allocate<std::int32_t>(g.px(), "detection: grid index");
  if (!index) return index.error();
  auto t = triangulate_disparity(rectifier.geometry(), disparity, *xyz, *px, b.factor);
  if (!t) return t.error();
  GridCloud c{xyz->first(t->points), px->first(t->points), *index, g.w, g.h};
  std::fill(index->begin(), index->end(), kNone);
  for (std::size_t i = 0; i < c.pixels.size(); ++i)
    (*index)[static_cast<std::size_t>(c.pixels[i].v) * static_cast<std::size_t>(g.w) +
             static_cast<std::size_t>(c.pixels[i].u)] = static_cast<std::int32_t>(i);
  return c;
}

// Normals from the grid's neighbours kNormalReach pixels away (central
// differences over 2 kNormalReach + 1 grid pixels: the pebbles' relief at one
// pixel's spacing would lean most near-ground normals past the check's
// angle), towards the camera; zero where a neighbour has no point.
constexpr int kNormalReach = 2;

Result<std::span<Eigen::Vector3d>> grid_normals(const GridCloud& c, const Grid& g,
                                                const Eigen::Vector3d& camera, Arena& arena) {
  auto normals = arena.allocate<Eigen::Vector3d>(c.xyz.size(), "detection: normals");
  if (!normals) return normals.error();
  const int k = kNormalReach;
  for (std::size_t i = 0; i < c.xyz.size(); ++i) {
    const int x = c.pixels[i].u, y = c.pixels[i].v;
    if (x < k || y < k || x + k >= g.w || y + k >= g.h) continue;
    const std::int32_t l = c.at(x - k, y), r = c.at(x + k, y), u = c.at(x, y - k),
                       d = c.at(x, y + k);
    if (l == kNone || r == kNone || u == kNone || d == kNone) continue;
    const auto p = [&](std::int32_t j) -> const Eigen::Vector3d& {
      return c.xyz[static_cast<std::size_t>(j)];
    };
    Eigen::Vector3d n = (p(r) - p(l)).cross(p(d) - p(u));
    if (!(n.norm() > 0)) continue;
    n.normalize();
    if (n.dot(camera - c.xyz[i]) < 0) n = -n;
    (*normals)[i] = n;
  }
  return *normals;
}

// The ground over the field of view (the chain's fit and normals check);
// then only the points standing clear of it keep the rock label.
Result<GroundResultT<double>> ground_step(const Rectifier& rectifier, const GridCloud& c,
                                          Rect region, const DetectionBudget& b,
                                          const DetectionParams& p, std::span<PointClass> labels,
                                          Arena& arena) {
  const Eigen::Vector3d camera = camera_centre_world(rectifier.rig().left);
  // Disparity noise is the matcher's at 1/factor resolution: f in those pixels.
  const StereoNoise noise{rectifier.geometry().left.f_px / b.factor,
                          rectifier.geometry().baseline_mm};
  GroundFailure why = GroundFailure::none;
  auto g = segment_ground<double>(c.xyz, c.pixels, region, ClickPx{}, camera, p.ground, labels,
                                  noise, &why);
  if (!g && why == GroundFailure::none && g.code() == Errc::degenerate &&
      c.xyz.size() >= p.ground.min_points) {
    // The points lie on one plane: ground, and no rock in view.
    std::fill(labels.begin(), labels.end(), PointClass::ground);
    return GroundResultT<double>{};
  }
  if (!g) return Error::make(g.code(), "detection: %s", g.error().message);
  auto normals = grid_normals(c, grid_of(b), camera, arena);
  if (!normals) return normals.error();
  const GroundNormalShare s =
      ground_normal_share(*normals, labels, g->plane.normal, p.ground_normals);
  if (s.share < p.ground_normals.min_share)
    return Error::make(Errc::no_solution,
                       "detection: no ground in view: only %.0f %% of the best plane's points "
                       "face along it",
                       100.0 * s.share);
  // The band grows with each point's own depth noise (r^2: the far field's
  // ground stands above a plane fitted where most points are, near).
  const double band = std::max(p.min_band_mm, p.band_rms * g->rms_mm);
  const double per_r2 =
      p.band_sigmas * p.ground.sigma_disparity_px / (noise.focal_px * noise.baseline_mm);
  const double max_r2 = p.max_range_mm * p.max_range_mm;
  for (std::size_t i = 0; i < labels.size(); ++i) {
    const double r2 = (c.xyz[i] - camera).squaredNorm();
    if (labels[i] == PointClass::rock &&
        (!(g->plane.distance(c.xyz[i]) > std::max(band, per_r2 * r2)) || r2 > max_r2))
      labels[i] = PointClass::ground;
  }
  return *g;
}

// One connected region of rock points on the grid.
struct Region {
  long pixels = 0;
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;        // grid box, inclusive
  long inner = 0;                            // interior points (all 8 neighbours in the region)
  int ix0 = 0, iy0 = 0, ix1 = -1, iy1 = -1;  // their box
  double height_mm = 0;
  std::size_t top = 0;  // the click's point
  double size_mm = 0;
};

// Largest horizontal extent: the widest of the points' spans along four
// directions in the ground plane (0, 45, 90, 135 deg).
struct Extent {
  Eigen::Vector3d dir[4];
  double lo[4], hi[4];
  explicit Extent(const Eigen::Vector3d& n) {
    const Eigen::Vector3d e1 = n.unitOrthogonal(), e2 = n.cross(e1);
    dir[0] = e1;
    dir[1] = e2;
    dir[2] = (e1 + e2).normalized();
    dir[3] = (e1 - e2).normalized();
    for (int k = 0; k < 4; ++k) lo[k] = hi[k] = 0;
  }
  void add(const Eigen::Vector3d& p, bool first) {
    for (int k = 0; k < 4; ++k) {
      const double t = dir[k].dot(p);
      lo[k] = first ? t : std::min(lo[k], t);
      hi[k] = first ? t : std::max(hi[k], t);
    }
  }
  double largest() const {
    double m = 0;
    for (int k = 0; k < 4; ++k) m = std::max(m, hi[k] - lo[k]);
    return m;
  }
};

// Floods the region holding point `seed` (8-connected points of its split
// part), marking `ids`; `stack` holds one entry per point.
Region flood(const GridCloud& c, std::span<const std::int32_t> part, const PlaneT<double>& ground,
             std::size_t seed, std::int32_t id, std::span<std::int32_t> ids,
             std::span<std::int32_t> stack) {
  Region r;
  Extent extent(ground.normal);
  std::size_t top = 0;
  ids[seed] = id;
  stack[top++] = static_cast<std::int32_t>(seed);
  r.x0 = r.x1 = c.pixels[seed].u;
  r.y0 = r.y1 = c.pixels[seed].v;
  while (top > 0) {
    const std::size_t i = static_cast<std::size_t>(stack[--top]);
    const int x = c.pixels[i].u, y = c.pixels[i].v;
    extent.add(c.xyz[i], r.pixels == 0);
    ++r.pixels;
    r.x0 = std::min(r.x0, x), r.x1 = std::max(r.x1, x);
    r.y0 = std::min(r.y0, y), r.y1 = std::max(r.y1, y);
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const int nx = x + dx, ny = y + dy;
        if (nx < 0 || ny < 0 || nx >= c.w || ny >= c.h) continue;
        const std::int32_t k = c.at(nx, ny);
        if (k == kNone || ids[static_cast<std::size_t>(k)] != kNone ||
            part[static_cast<std::size_t>(k)] != part[seed])
          continue;
        ids[static_cast<std::size_t>(k)] = id;
        stack[top++] = k;
      }
  }
  r.size_mm = extent.largest();
  return r;
}

// Whether the region's point at grid (x, y) has all 8 neighbours in it:
// the silhouette's mismatched fringe and lone spikes never are.
bool interior(const GridCloud& c, std::span<const std::int32_t> ids, int x, int y,
              std::int32_t id) {
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      const int nx = x + dx, ny = y + dy;
      if (nx < 0 || ny < 0 || nx >= c.w || ny >= c.h) return false;
      const std::int32_t k = c.at(nx, ny);
      if (k == kNone || ids[static_cast<std::size_t>(k)] != id) return false;
    }
  return true;
}

// The region's height (its highest interior point), its interior box and
// its click: the interior point nearest the centre of its box. No interior
// point: height 0.
void height_and_click(const GridCloud& c, std::span<const std::int32_t> ids,
                      const PlaneT<double>& ground, std::int32_t id, Region& r) {
  const double cx = 0.5 * (r.x0 + r.x1), cy = 0.5 * (r.y0 + r.y1);
  double best = -1;
  for (int y = r.y0; y <= r.y1; ++y)
    for (int x = r.x0; x <= r.x1; ++x) {
      const std::int32_t k = c.at(x, y);
      if (k == kNone || !interior(c, ids, x, y, id)) continue;
      const std::size_t i = static_cast<std::size_t>(k);
      r.height_mm = std::max(r.height_mm, ground.distance(c.xyz[i]));
      r.ix0 = r.inner == 0 ? x : std::min(r.ix0, x), r.ix1 = std::max(r.ix1, x);
      r.iy0 = r.inner == 0 ? y : std::min(r.iy0, y), r.iy1 = std::max(r.iy1, y);
      ++r.inner;
      const double d2 = (x - cx) * (x - cx) + (y - cy) * (y - cy);
      if (best < 0 || d2 < best) best = d2, r.top = i;
    }
}

// The region as a candidate: its box padded, in original left pixels, and
// its highest point as the click.
Result<RockCandidate> candidate_of(const Rectifier& rectifier, const GridCloud& c, const Region& r,
                                   const DetectionBudget& b, const DetectionParams& p) {
  const int f = b.factor;
  // The interior's box, a grid pixel all round (the outline it lost).
  const Rect box{(r.ix0 - 1) * f, (r.iy0 - 1) * f, (r.ix1 - r.ix0 + 3) * f,
                 (r.iy1 - r.iy0 + 3) * f};
  auto o = rectifier.roi_to_original(StereoSide::left, box);
  if (!o) return o.error();
  const int pad =
      std::max(p.min_pad_px, static_cast<int>(std::lround(p.pad * std::max(o->w, o->h))));
  const int x0 = std::max(0, o->x - pad), y0 = std::max(0, o->y - pad);
  const int x1 = std::min(b.image_width, o->x + o->w + pad);
  const int y1 = std::min(b.image_height, o->y + o->h + pad);
  const PixelPos t = c.pixels[r.top];
  auto click =
      rectifier.to_original(StereoSide::left, {t.u * f + 0.5 * (f - 1), t.v * f + 0.5 * (f - 1)});
  if (!click) return click.error();
  RockCandidate k;
  k.roi = {x0, y0, x1 - x0, y1 - y0};
  k.click_u = std::clamp(static_cast<int>(std::lround(click->x())), x0, x1 - 1);
  k.click_v = std::clamp(static_cast<int>(std::lround(click->y())), y0, y1 - 1);
  k.height_mm = r.height_mm;
  k.size_mm = r.size_mm;
  k.pixels = r.pixels;
  return k;
}

// Keeps the kMaxRockCandidates largest (pixels), largest first.
void keep_largest(const RockCandidate& k, std::int32_t id, std::int32_t (&ids)[kMaxRockCandidates],
                  DetectionResult& out) {
  int at = out.count;
  while (at > 0 && out.rocks[at - 1].pixels < k.pixels) --at;
  if (at >= kMaxRockCandidates) return;
  const int last = std::min(out.count, kMaxRockCandidates - 1);
  for (int i = last; i > at; --i) out.rocks[i] = out.rocks[i - 1], ids[i] = ids[i - 1];
  out.rocks[at] = k;
  ids[at] = id;
  out.count = std::min(out.count + 1, kMaxRockCandidates);
}

// The rock points split where height maxima meet at a saddle (rock_split);
// `ids` and `stack` lent as its scratch (both refilled after it).
Result<std::span<std::int32_t>> split_step(const GridCloud& c, std::span<const PointClass> labels,
                                           const PlaneT<double>& ground, const DetectionParams& p,
                                           std::span<std::int32_t> ids,
                                           std::span<std::int32_t> stack, Arena& arena) {
  auto height = arena.allocate<float>(c.xyz.size(), "detection: heights");
  if (!height) return height.error();
  auto part = arena.allocate<std::int32_t>(c.xyz.size(), "detection: parts");
  if (!part) return part.error();
  for (std::size_t i = 0; i < c.xyz.size(); ++i)
    (*height)[i] = static_cast<float>(ground.distance(c.xyz[i]));
  const SplitGrid grid{c.w, c.h, c.index, c.pixels};
  PETRA_TRY(split_at_saddles(grid, *height, labels, {p.split_prominence_mm, p.min_pixels}, *part,
                             stack, ids));
  return *part;
}

// Per map cell: the index of the candidate a point's region became (where
// two meet in a cell, the later point's).
void fill_rock_map(const GridCloud& c, std::span<const std::int32_t> ids,
                   const std::int32_t (&kept)[kMaxRockCandidates], int count,
                   const RockMapShape& shape, std::span<std::uint8_t> map) {
  std::fill(map.begin(), map.end(), kNoRock);
  for (std::size_t i = 0; i < c.xyz.size(); ++i) {
    if (ids[i] == kNone) continue;
    std::uint8_t v = kOtherRock;
    for (int k = 0; k < count; ++k)
      if (kept[k] == ids[i]) v = static_cast<std::uint8_t>(k);
    map[static_cast<std::size_t>(c.pixels[i].v / shape.step) * static_cast<std::size_t>(shape.w) +
        static_cast<std::size_t>(c.pixels[i].u / shape.step)] = v;
  }
}

// Every region of rock points; those that pass the checks become candidates.
// `rock_map` (empty or grid-sized): filled by fill_rock_map.
Status regions_step(const Rectifier& rectifier, const GridCloud& c,
                    std::span<const PointClass> labels, const DetectionBudget& b,
                    const DetectionParams& p, Arena& arena, DetectionResult& out,
                    std::span<std::uint8_t> rock_map) {
  auto ids = arena.allocate<std::int32_t>(c.xyz.size(), "detection: region ids");
  if (!ids) return ids.error();
  auto stack = arena.allocate<std::int32_t>(c.xyz.size(), "detection: flood");
  if (!stack) return stack.error();
  auto part = split_step(c, labels, out.ground.plane, p, *ids, *stack, arena);
  if (!part) return part.error();
  std::int32_t kept[kMaxRockCandidates] = {};  // each candidate's region id
  std::fill(ids->begin(), ids->end(), kNone);
  for (std::size_t i = 0; i < c.xyz.size(); ++i) {
    if (labels[i] != PointClass::rock || (*ids)[i] != kNone) continue;
    const std::int32_t id = out.regions++;
    Region r = flood(c, *part, out.ground.plane, i, id, *ids, *stack);
    if (r.pixels < p.min_pixels || r.size_mm < p.min_size_mm) continue;
    height_and_click(c, *ids, out.ground.plane, id, r);
    if (r.inner == 0 || r.height_mm < p.min_height_mm) continue;
    auto k = candidate_of(rectifier, c, r, b, p);
    if (!k) return k.error();
    keep_largest(*k, id, kept, out);
  }
  if (!rock_map.empty()) fill_rock_map(c, *ids, kept, out.count, rock_map_shape(b), rock_map);
  return {};
}

}  // namespace

Result<DetectionResult> detect_rocks_in_disparity(const Rectifier& rectifier,
                                                  ConstDisparityMap disparity,
                                                  const DetectionBudget& b,
                                                  const DetectionParams& p, Arena& arena,
                                                  std::span<std::uint8_t> rock_map) {
  PETRA_TRY(validate(b));
  PETRA_TRY(validate(p));
  const Grid g = grid_of(b);
  if (!rock_map.empty() && rock_map.size() != rock_map_shape(b).cells())
    return Error::make(Errc::invalid_argument, "detection: rock map of %zu cells, not %zu",
                       rock_map.size(), rock_map_shape(b).cells());
  const Rect& r = disparity.roi;
  if (r.empty() || !r.inside(g.w, g.h) || disparity.q4.width() != r.w ||
      disparity.q4.height() != r.h)
    return Error::make(Errc::invalid_argument,
                       "detection: disparity map (%d,%d %dx%d) not within the %dx%d grid", r.x, r.y,
                       r.w, r.h, g.w, g.h);
  const ArenaScope scope(arena);
  DetectionResult out;
  out.region_coarse = r;
  auto c = grid_cloud(rectifier, disparity, b, arena);
  if (!c) return c.error();
  out.points = static_cast<long>(c->xyz.size());
  auto labels = arena.allocate<PointClass>(c->xyz.size(), "detection: labels");
  if (!labels) return labels.error();
  auto ground = ground_step(rectifier, *c, r, b, p, *labels, arena);
  if (!ground) return ground.error();
  out.ground = *ground;
  PETRA_TRY(regions_step(rectifier, *c, *labels, b, p, arena, out, rock_map));
  return out;
}

Result<DetectionResult> detect_rocks(const Rectifier& rectifier, ConstGray8View left,
                                     ConstGray8View right, Rect region, const DetectionBudget& b,
                                     const DetectionParams& p, Arena& arena, const StepClock& clock,
                                     std::span<std::uint8_t> rock_map) {
  PETRA_TRY(validate(b));
  PETRA_TRY(validate(p));
  if (left.width() != b.image_width || left.height() != b.image_height ||
      right.width() != b.image_width || right.height() != b.image_height ||
      rectifier.width() != b.image_width || rectifier.height() != b.image_height)
    return Error::make(Errc::invalid_argument, "detection: images %dx%d and %dx%d, budget %dx%d",
                       left.width(), left.height(), right.width(), right.height(), b.image_width,
                       b.image_height);
  if (!region.empty() && !region.inside(b.image_width, b.image_height))
    return Error::make(Errc::out_of_range, "detection: region (%d,%d %dx%d) not inside %dx%d",
                       region.x, region.y, region.w, region.h, b.image_width, b.image_height);
  const ArenaScope scope(arena);
  auto coarse = coarse_region(rectifier, region, b);
  if (!coarse) return coarse.error();
  PETRA_TRY(checkpoint(clock, PipelineStep::rectify));
  auto v = coarse_pair(rectifier, left, right, *coarse, b, arena);
  if (!v) return v.error();
  PETRA_TRY(checkpoint(clock, PipelineStep::match));
  const StereoInput in{v->left, v->right, nullptr, nullptr};
  auto m = match_dp(in, *coarse, coarse_match(b, p), match_budget(b), arena, v->disparity);
  if (!m) return Error::make(m.code(), "detection: %s", m.error().message);
  PETRA_TRY(checkpoint(clock, PipelineStep::segmentation));
  auto out = detect_rocks_in_disparity(rectifier, v->disparity, b, p, arena, rock_map);
  if (out) out->match = *m;
  return out;
}

}  // namespace petra
