#include "algo/surface/grind_footprint.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>

namespace petra {

namespace {

constexpr int kSectors = 8;

struct Local {
  double x, y, z, a;  // in the face frame (e1, e2, n) about the face centre; area
};

struct Frame {
  Eigen::Vector3d o, e1, e2, n;
  Local to_local(const FaceSample& s) const {
    const Eigen::Vector3d q = s.p - o;
    return {q.dot(e1), q.dot(e2), q.dot(n), s.area};
  }
};

Frame frame_of(const Eigen::Vector3d& n, const Eigen::Vector3d& o) {
  Frame f;
  f.o = o;
  f.n = n;
  const Eigen::Vector3d helper =
      std::abs(n.z()) < 0.9 ? Eigen::Vector3d::UnitZ() : Eigen::Vector3d::UnitX();
  f.e1 = helper.cross(n).normalized();
  f.e2 = n.cross(f.e1);
  return f;
}

// Area-weighted sums of a disc about its centre (dx, dy relative to it).
struct DiscSums {
  double w = 0, x = 0, y = 0, z = 0, xx = 0, xy = 0, yy = 0, xz = 0, yz = 0, zz = 0;
  double sector[kSectors] = {};
  std::size_t count = 0;
  void add(double dx, double dy, double dz, double a) {
    w += a, x += a * dx, y += a * dy, z += a * dz;
    xx += a * dx * dx, xy += a * dx * dy, yy += a * dy * dy;
    xz += a * dx * dz, yz += a * dy * dz, zz += a * dz * dz;
    // Octant by signs and which coordinate is larger: no trigonometry.
    const int s = (dx < 0 ? 4 : 0) + (dy < 0 ? 2 : 0) + (std::abs(dx) < std::abs(dy) ? 1 : 0);
    sector[s] += a;
    ++count;
  }
};

// z = zc + a dx + b dy by weighted least squares; rss over w. level_rms:
// the offsets' RMS about their mean (about a plane parallel to the face's).
struct DiscPlane {
  bool ok = false;
  double a = 0, b = 0, zc = 0, rms = 0, level_rms = 0;
};

DiscPlane solve(const DiscSums& s) {
  DiscPlane p;
  if (s.count < 3 || !(s.w > 0)) return p;
  const double mx = s.x / s.w, my = s.y / s.w, mz = s.z / s.w;
  const double cxx = s.xx / s.w - mx * mx, cxy = s.xy / s.w - mx * my;
  const double cyy = s.yy / s.w - my * my, cxz = s.xz / s.w - mx * mz;
  const double cyz = s.yz / s.w - my * mz, czz = s.zz / s.w - mz * mz;
  const double det = cxx * cyy - cxy * cxy;
  if (!(det > 1e-12 * (cxx + cyy) * (cxx + cyy))) return p;
  p.a = (cxz * cyy - cyz * cxy) / det;
  p.b = (cyz * cxx - cxz * cxy) / det;
  p.zc = mz - p.a * mx - p.b * my;
  const double rss = std::max(0.0, czz - p.a * cxz - p.b * cyz);
  // Offsets along n to distances across the disc's own plane.
  p.rms = std::sqrt(rss / (1.0 + p.a * p.a + p.b * p.b));
  p.level_rms = std::sqrt(std::max(0.0, czz));
  p.ok = true;
  return p;
}

bool covers(const DiscSums& s, double disc_area, double weight, double min_coverage) {
  if (s.w * weight < min_coverage * disc_area) return false;
  for (double a : s.sector)
    if (a * weight < 0.5 * disc_area / kSectors) return false;
  return true;
}

struct Grid {
  double x0 = 0, y0 = 0, cell = 1;
  int nx = 0, ny = 0;
  int cx(double x) const { return std::clamp(static_cast<int>((x - x0) / cell), 0, nx - 1); }
  int cy(double y) const { return std::clamp(static_cast<int>((y - y0) / cell), 0, ny - 1); }
};

// 1. Thinned samples in the face frame (every stride-th), binned by cell:
// order lists them cell by cell, from start[c] for cell c.
struct Binned {
  std::span<Local> local;
  std::span<std::int32_t> order;
  std::span<std::int32_t> start;
  Grid g;
  double lo_x = 1e300, lo_y = 1e300, hi_x = -1e300, hi_y = -1e300;
  std::size_t stride = 1;
};

// Cells of side r, widened until their number fits kFootprintCells.
Grid cell_grid(const Binned& b, double r) {
  const double lo_x = b.lo_x, lo_y = b.lo_y, hi_x = b.hi_x, hi_y = b.hi_y;
  Grid g;
  g.x0 = lo_x, g.y0 = lo_y, g.cell = r;
  auto cells_for = [&](double c) {
    return static_cast<double>(static_cast<int>((hi_x - lo_x) / c) + 1) *
           static_cast<double>(static_cast<int>((hi_y - lo_y) / c) + 1);
  };
  while (cells_for(g.cell) > static_cast<double>(kFootprintCells)) g.cell *= 1.25;
  g.nx = static_cast<int>((hi_x - lo_x) / g.cell) + 1;
  g.ny = static_cast<int>((hi_y - lo_y) / g.cell) + 1;
  return g;
}

// Counting sort of the samples by cell.
void sort_by_cell(Binned& b) {
  const Grid& g = b.g;
  const std::size_t m = b.local.size();
  const std::size_t cells = static_cast<std::size_t>(g.nx) * static_cast<std::size_t>(g.ny);
  auto cell_of = [&](const Local& l) {
    return static_cast<std::size_t>(g.cy(l.y)) * static_cast<std::size_t>(g.nx) +
           static_cast<std::size_t>(g.cx(l.x));
  };
  for (std::size_t i = 0; i < m; ++i) ++b.start[cell_of(b.local[i]) + 1];
  for (std::size_t c = 0; c < cells; ++c) b.start[c + 1] += b.start[c];
  for (std::size_t i = 0; i < m; ++i) {
    const std::size_t c = cell_of(b.local[i]);
    b.order[static_cast<std::size_t>(b.start[c]++)] = static_cast<std::int32_t>(i);
  }
  for (std::size_t c = cells; c > 0; --c) b.start[c] = b.start[c - 1];
  b.start[0] = 0;
}

Status bin_samples(std::span<const FaceSample> samples, const Frame& fr, double r, Arena& arena,
                   Binned& b) {
  const std::size_t m_all = samples.size();
  const std::size_t stride = (m_all + kFootprintSamples - 1) / kFootprintSamples;
  const std::size_t m = (m_all + stride - 1) / stride;
  auto local = arena.allocate_uninitialised<Local>(m, "footprint samples");
  if (!local) return local.error();
  auto order = arena.allocate_uninitialised<std::int32_t>(m, "footprint order");
  if (!order) return order.error();
  auto start = arena.allocate<std::int32_t>(kFootprintCells + 1, "footprint cells");
  if (!start) return start.error();
  b.local = *local;
  b.order = *order;
  b.start = *start;
  b.stride = stride;
  double lo_x = 1e300, lo_y = 1e300, hi_x = -1e300, hi_y = -1e300;
  for (std::size_t i = 0; i < m; ++i) {
    const Local l = fr.to_local(samples[i * stride]);
    b.local[i] = l;
    lo_x = std::min(lo_x, l.x), hi_x = std::max(hi_x, l.x);
    lo_y = std::min(lo_y, l.y), hi_y = std::max(hi_y, l.y);
  }
  b.lo_x = lo_x, b.lo_y = lo_y, b.hi_x = hi_x, b.hi_y = hi_y;
  b.g = cell_grid(b, r);
  sort_by_cell(b);
  return ok_status();
}

// 2. Candidate centres: a grid over the extent, a radius in from its edges,
// spaced h apart.
struct Candidates {
  double x0 = 0, y0 = 0, h = 0;
  int ncx = 0, ncy = 0;
};

// False when no disc fits in the extent.
bool candidate_grid(const Binned& b, double r, Candidates& c) {
  const double lo_x = b.lo_x, lo_y = b.lo_y, hi_x = b.hi_x, hi_y = b.hi_y;
  const double span_x = hi_x - lo_x - 2 * r, span_y = hi_y - lo_y - 2 * r;
  if (span_x < 0 || span_y < 0) return false;
  double h = r / 2;
  auto count_for = [&](double step) {
    return static_cast<std::size_t>(span_x / step + 1) *
           static_cast<std::size_t>(span_y / step + 1);
  };
  while (count_for(h) > kFootprintCandidates) h *= 1.25;
  c.h = h;
  c.ncx = static_cast<int>(span_x / h) + 1, c.ncy = static_cast<int>(span_y / h) + 1;
  c.x0 = lo_x + r + (span_x - (c.ncx - 1) * h) / 2;
  c.y0 = lo_y + r + (span_y - (c.ncy - 1) * h) / 2;
  return true;
}

// The binned samples within r of (cx, cy).
DiscSums disc_sums(const Binned& b, double r, double cx, double cy) {
  const Grid& g = b.g;
  DiscSums s;
  const int gx0 = g.cx(cx - r), gx1 = g.cx(cx + r), gy0 = g.cy(cy - r), gy1 = g.cy(cy + r);
  for (int gy = gy0; gy <= gy1; ++gy)
    for (int gx = gx0; gx <= gx1; ++gx) {
      const std::size_t c = static_cast<std::size_t>(gy) * static_cast<std::size_t>(g.nx) +
                            static_cast<std::size_t>(gx);
      for (std::int32_t k = b.start[c]; k < b.start[c + 1]; ++k) {
        const Local& l = b.local[static_cast<std::size_t>(b.order[static_cast<std::size_t>(k)])];
        const double dx = l.x - cx, dy = l.y - cy;
        if (dx * dx + dy * dy <= r * r) s.add(dx, dy, l.z, l.a);
      }
    }
  return s;
}

// 3. Each disc: coverage, flatness about its own plane (rms, -1 where not
// covered) and about a plane parallel to the face's (level), and its own
// plane's offset at its centre (zc).
struct DiscScores {
  double rms[kFootprintCandidates] = {};
  double level[kFootprintCandidates] = {};
  double zc[kFootprintCandidates] = {};
};

void score_candidates(const Binned& b, double r, const Candidates& c, double min_coverage,
                      DiscScores& d, Footprint& out) {
  const double disc_area = M_PI * r * r;
  for (int j = 0; j < c.ncy; ++j)
    for (int i = 0; i < c.ncx; ++i) {
      const std::size_t k = static_cast<std::size_t>(j * c.ncx + i);
      const double cx = c.x0 + i * c.h, cy = c.y0 + j * c.h;
      const DiscSums s = disc_sums(b, r, cx, cy);
      const DiscPlane p = solve(s);
      d.rms[k] = -1;
      ++out.candidates;
      if (!p.ok || !covers(s, disc_area, static_cast<double>(b.stride), min_coverage)) continue;
      d.rms[k] = p.rms;
      d.level[k] = p.level_rms;
      d.zc[k] = p.zc;
    }
}

// 4. Of the discs flat within the tolerance, the most level; none: the
// flattest; -1 if no disc is covered.
int flush_candidate(const DiscScores& d, int n, double max_rms) {
  int flush = -1, flattest = -1;
  for (int k = 0; k < n; ++k) {
    const std::size_t u = static_cast<std::size_t>(k);
    if (d.rms[u] < 0) continue;
    if (flattest < 0 || d.rms[u] < d.rms[static_cast<std::size_t>(flattest)]) flattest = k;
    if (d.rms[u] <= max_rms && (flush < 0 || d.level[u] < d.level[static_cast<std::size_t>(flush)]))
      flush = k;
  }
  return flush >= 0 ? flush : flattest;
}

// 4, with a reach: the flat discs from the most level on, until one is
// reached (its centre on its own plane, the tool along the face's normal);
// -1 when none is (out.reach says which). Each disc is asked once: one plan
// per disc at most.
int reached_candidate(const DiscScores& d, const Candidates& c, const Frame& fr, double max_rms,
                      const DiscReach& reach, Footprint& out) {
  const int n = c.ncx * c.ncy;
  std::int16_t order[kFootprintCandidates];
  int m = 0;
  for (int k = 0; k < n; ++k) {
    const std::size_t u = static_cast<std::size_t>(k);
    if (d.rms[u] >= 0 && d.rms[u] <= max_rms) order[m++] = static_cast<std::int16_t>(k);
  }
  std::sort(order, order + m, [&](std::int16_t a, std::int16_t b) {
    const double la = d.level[static_cast<std::size_t>(a)];
    const double lb = d.level[static_cast<std::size_t>(b)];
    return la < lb || (la == lb && a < b);
  });
  for (int i = 0; i < m; ++i) {
    const int k = order[i];
    const double cx = c.x0 + (k % c.ncx) * c.h, cy = c.y0 + (k / c.ncx) * c.h;
    const Eigen::Vector3d centre =
        fr.o + cx * fr.e1 + cy * fr.e2 + d.zc[static_cast<std::size_t>(k)] * fr.n;
    if (reach.reaches(centre, fr.n)) {
      out.reach = i == 0 ? FootprintReach::most_level : FootprintReach::moved;
      return k;
    }
  }
  if (m > 0) out.reach = FootprintReach::none_reached;
  return -1;
}

// 5. The chosen disc, centred (cx, cy) in the face frame, on every sample.
void fit_chosen_disc(std::span<const FaceSample> samples, const Frame& fr, double r, double cx,
                     double cy, Footprint& out) {
  const double disc_area = M_PI * r * r;
  const Eigen::Vector3d c3 = fr.o + cx * fr.e1 + cy * fr.e2;
  DiscSums s;
  for_each_in_disc(samples, fr.n, c3, r, [&](const FaceSample& fs) {
    const Local l = fr.to_local(fs);
    s.add(l.x - cx, l.y - cy, l.z, l.a);
  });
  const DiscPlane p = solve(s);
  if (!p.ok) return;
  out.covered = true;
  out.coverage = s.w / disc_area;
  out.samples = s.count;
  out.rms_mm = p.rms;
  out.normal = (fr.n - p.a * fr.e1 - p.b * fr.e2).normalized();
  out.centre_mm = c3 + p.zc * fr.n;
  double lo = 0, hi = 0;
  bool first = true;
  for_each_in_disc(samples, fr.n, c3, r, [&](const FaceSample& fs) {
    const double d = out.normal.dot(fs.p - out.centre_mm);
    lo = first ? d : std::min(lo, d);
    hi = first ? d : std::max(hi, d);
    first = false;
  });
  out.peak_to_valley_mm = hi - lo;
}

}  // namespace

const char* footprint_reach_key(FootprintReach r) {
  switch (r) {
    case FootprintReach::most_level:
      return "most_level";
    case FootprintReach::moved:
      return "moved";
    case FootprintReach::none_reached:
      return "none_reached";
    case FootprintReach::not_asked:
      break;
  }
  return "";
}

FaceSample triangle_sample(std::span<const Eigen::Vector3d> xyz_mm, const MeshTriangle& t,
                           const Eigen::Vector3d& camera_mm) {
  const Eigen::Vector3d& a = xyz_mm[static_cast<std::size_t>(t.v[0])];
  const Eigen::Vector3d& b = xyz_mm[static_cast<std::size_t>(t.v[1])];
  const Eigen::Vector3d& c = xyz_mm[static_cast<std::size_t>(t.v[2])];
  const Eigen::Vector3d p = (a + b + c) / 3.0;
  const Eigen::Vector3d cross = (b - a).cross(c - a);
  const Eigen::Vector3d ray = camera_mm - p;
  const double range = ray.norm();
  const double seen = range > 0 ? 0.5 * std::abs(cross.dot(ray)) / range : 0.0;
  return FaceSample{p, static_cast<float>(0.5 * cross.norm()), static_cast<float>(seen)};
}

std::size_t footprint_scratch_bytes(std::size_t samples) {
  const std::size_t m = std::min(samples, kFootprintSamples);
  return m * sizeof(Local) + alignof(Local) + m * sizeof(std::int32_t) +
         (kFootprintCells + 1) * sizeof(std::int32_t) + 2 * alignof(std::int32_t);
}

Result<Footprint> find_footprint(std::span<const FaceSample> samples,
                                 const Eigen::Vector3d& face_normal,
                                 const Eigen::Vector3d& face_centre, const FootprintParams& params,
                                 Arena& arena) {
  if (!(params.diameter_mm > 0.0 && params.diameter_mm < 1000.0))
    return Error::make(Errc::invalid_argument, "footprint: diameter_mm %.3g not in (0, 1000)",
                       params.diameter_mm);
  if (!(params.min_coverage > 0.0 && params.min_coverage <= 1.0))
    return Error::make(Errc::invalid_argument, "footprint: min_coverage not in (0, 1]");
  if (!(params.max_rms_mm >= 0.0 && params.max_rms_mm < 1000.0))
    return Error::make(Errc::invalid_argument, "footprint: max_rms_mm %.3g not in [0, 1000)",
                       params.max_rms_mm);
  if (!(std::abs(face_normal.norm() - 1.0) < 1e-6))
    return Error::make(Errc::invalid_argument, "footprint: the face normal is not a unit vector");
  const std::size_t m_all = samples.size();
  if (m_all < 3) return Error::make(Errc::degenerate, "footprint: %zu face samples", m_all);
  ArenaScope scope(arena);
  const Frame fr = frame_of(face_normal, face_centre);
  const double r = params.diameter_mm / 2.0;
  Binned b;
  PETRA_TRY(bin_samples(samples, fr, r, arena, b));
  Footprint out;
  Candidates c;
  if (!candidate_grid(b, r, c)) return out;  // no disc fits in the extent
  DiscScores d;
  score_candidates(b, r, c, params.min_coverage, d, out);
  int best = -1;
  if (params.reach != nullptr)
    best = reached_candidate(d, c, fr, params.max_rms_mm, *params.reach, out);
  if (best < 0) best = flush_candidate(d, c.ncx * c.ncy, params.max_rms_mm);
  if (best < 0) return out;
  const double cx = c.x0 + (best % c.ncx) * c.h, cy = c.y0 + (best / c.ncx) * c.h;
  fit_chosen_disc(samples, fr, r, cx, cy, out);
  return out;
}

}  // namespace petra
