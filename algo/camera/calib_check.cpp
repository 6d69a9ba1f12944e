#include "algo/camera/calib_check.hpp"

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdlib>
#include <span>

namespace petra {

namespace {

constexpr int kMaxDisparities = 1024;  // range bound of the per-disparity cost row
constexpr int kMaxPatch = 15;          // 2 x max patch_radius + 1
constexpr int kScoreRadius = 2;        // corner score window 5x5

constexpr int kStrip = 64;  // columns of a cell scored at once (stack buffers)

struct Corner {
  long score = -1;  // min(sum gx^2, sum gy^2) over the 5x5 window
  int x = 0, y = 0;
};

// Adds (sign +1) or removes (-1) row v's squared gradients (central
// differences) of columns x0 .. x0 + n - 1 to the column sums.
void add_gradient_row(ConstGray8View im, int v, int x0, int n, long sign, long* sxx, long* syy) {
  const std::uint8_t* up = im.row(v - 1);
  const std::uint8_t* row = im.row(v);
  const std::uint8_t* down = im.row(v + 1);
  for (int c = 0; c < n; ++c) {
    const int u = x0 + c;
    const long gx = static_cast<long>(row[u + 1]) - row[u - 1];
    const long gy = static_cast<long>(down[u]) - up[u];
    sxx[c] += sign * gx * gx;
    syy[c] += sign * gy * gy;
  }
}

// The strongest corner of the cell [x0, x1) x [y0, y1), the first in raster
// order among equals. The score, min(sum gx^2, sum gy^2) over the 5x5
// window, is high only where the patch has structure in both directions, so
// a row offset is measurable. Column sums over the window's rows slide down
// the cell and the window slides along each row: the same integers as
// summing each window, about a tenth of the work.
Corner strongest_corner(ConstGray8View im, int x0, int x1, int y0, int y1) {
  constexpr int k = kScoreRadius, side = 2 * kScoreRadius + 1;
  Corner best;
  for (int sx = x0; sx < x1; sx += kStrip) {
    const int ex = std::min(sx + kStrip, x1), n = ex - sx + 2 * k;
    long sxx[kStrip + 2 * k] = {}, syy[kStrip + 2 * k] = {};
    for (int v = y0 - k; v < y0 + k; ++v) add_gradient_row(im, v, sx - k, n, 1, sxx, syy);
    for (int y = y0; y < y1; ++y) {
      add_gradient_row(im, y + k, sx - k, n, 1, sxx, syy);
      long wx = 0, wy = 0;
      for (int c = 0; c < side - 1; ++c) wx += sxx[c], wy += syy[c];
      for (int x = sx; x < ex; ++x) {
        const int c = x - sx;
        wx += sxx[c + side - 1];
        wy += syy[c + side - 1];
        const long sc = std::min(wx, wy);
        if (sc > best.score || (sc == best.score && (y < best.y || (y == best.y && x < best.x))))
          best = {sc, x, y};
        wx -= sxx[c];
        wy -= syy[c];
      }
      add_gradient_row(im, y - k, sx - k, n, -1, sxx, syy);
    }
  }
  return best;
}

struct Patch {
  int n = 0;  // pixels
  int side = 0;
  int z[kMaxPatch * kMaxPatch];  // n x pixel - sum (zero-mean, scaled by n)
};

void load_patch(ConstGray8View im, int x, int y, int r, Patch& p) {
  p.side = 2 * r + 1;
  p.n = p.side * p.side;
  int sum = 0;
  for (int v = -r; v <= r; ++v)
    for (int u = -r; u <= r; ++u) sum += im(x + u, y + v);
  int i = 0;
  for (int v = -r; v <= r; ++v)
    for (int u = -r; u <= r; ++u) p.z[i++] = p.n * im(x + u, y + v) - sum;
}

// Zero-mean SAD of the left patch against the right patch centred at (x, y).
int zsad(const Patch& l, ConstGray8View right, int x, int y, int r) {
  int sum = 0;
  for (int v = -r; v <= r; ++v) {
    const std::uint8_t* row = right.row(y + v);
    for (int u = -r; u <= r; ++u) sum += row[x + u];
  }
  int cost = 0, i = 0;
  for (int v = -r; v <= r; ++v) {
    const std::uint8_t* row = right.row(y + v);
    for (int u = -r; u <= r; ++u) cost += std::abs(l.z[i++] - (l.n * row[x + u] - sum));
  }
  return cost;
}

struct Search {
  ConstGray8View right;
  Rect right_area;
  int disp_min, disp_max, r, V;
  double uniqueness;
};

bool column_fits(const Search& s, int xr) {
  return xr - s.r >= s.right_area.x && xr + s.r < s.right_area.x + s.right_area.w;
}

// Scratch of the search: per disparity, the best cost over the row offsets,
// and for one row offset the patch sums and the costs (column sums first).
struct CostRows {
  std::span<int> per_d, sums, cost;
};

// cost[k] = zsad(p, right, j0 + k, yc, r) for k in [0, n): the patch sums by
// a window slid over column sums, then each patch pixel's absolute
// differences added across all n positions at once (a loop over
// contiguous memory the compiler vectorises). The same integers as zsad.
void patch_costs(const Patch& p, ConstGray8View right, int j0, int yc, int r, int n,
                 const CostRows& b) {
  const int side = 2 * r + 1, wide = n + side - 1;
  int* col = b.cost.data();
  int* sums = b.sums.data();
  for (int c = 0; c < wide; ++c) col[c] = 0;
  for (int v = -r; v <= r; ++v) {
    const std::uint8_t* row = right.row(yc + v) + j0 - r;
    for (int c = 0; c < wide; ++c) col[c] += row[c];
  }
  int sum = 0;
  for (int c = 0; c < side - 1; ++c) sum += col[c];
  for (int k = 0; k < n; ++k) {
    sum += col[k + side - 1];
    sums[k] = sum;
    sum -= col[k];
  }
  int* cost = b.cost.data();
  for (int k = 0; k < n; ++k) cost[k] = 0;
  for (int v = -r, i = 0; v <= r; ++v) {
    const std::uint8_t* row = right.row(yc + v) + j0 - r;
    for (int u = 0; u < side; ++u, ++i) {
      const int z = p.z[i], pn = p.n;
      const std::uint8_t* px = row + u;
      for (int k = 0; k < n; ++k) cost[k] += std::abs(z - (pn * px[k] - sums[k]));
    }
  }
}

// Best cost over the row offsets at each disparity (INT_MAX where the patch
// leaves the right area), then uniqueness along d and the sub-pixel row offset.
bool match_feature(const Search& s, const Patch& p, int x, int y, const CostRows& b,
                   double& offset) {
  std::span<int> per_d = b.per_d;
  for (int& c : per_d) c = INT_MAX;
  // The disparities whose patch fits the right area (column_fits).
  const int d_lo = std::max(s.disp_min, x + s.r + 1 - s.right_area.x - s.right_area.w);
  const int d_hi = std::min(s.disp_max, x - s.r - s.right_area.x);
  for (int dy = -s.V; dy <= s.V && d_lo <= d_hi; ++dy) {
    const int n = d_hi - d_lo + 1;
    patch_costs(p, s.right, x - d_hi, y + dy, s.r, n, b);  // position k: d = d_hi - k
    for (int k = 0; k < n; ++k) {
      int& m = per_d[static_cast<std::size_t>(d_hi - k - s.disp_min)];
      m = std::min(m, b.cost[static_cast<std::size_t>(k)]);
    }
  }
  int best = INT_MAX, d1 = 0;
  for (int d = s.disp_min; d <= s.disp_max; ++d) {
    const int m = per_d[static_cast<std::size_t>(d - s.disp_min)];
    if (m < best) best = m, d1 = d;
  }
  if (best == INT_MAX) return false;
  int second = INT_MAX;
  for (int d = s.disp_min; d <= s.disp_max; ++d)
    if (std::abs(d - d1) >= 2)
      second = std::min(second, per_d[static_cast<std::size_t>(d - s.disp_min)]);
  if (second != INT_MAX && !(best < s.uniqueness * second)) return false;
  // Row profile: each offset's best of d1-1..d1+1 (the true d is fractional).
  int prof[2 * 8 + 1] = {};
  for (int dy = -s.V; dy <= s.V; ++dy) {
    int m = INT_MAX;
    for (int d = d1 - 1; d <= d1 + 1; ++d)
      if (d >= s.disp_min && d <= s.disp_max && column_fits(s, x - d))
        m = std::min(m, zsad(p, s.right, x - d, y + dy, s.r));
    prof[dy + s.V] = m;
  }
  int k = 0;
  for (int i = 1; i <= 2 * s.V; ++i)
    if (prof[i] < prof[k]) k = i;
  if (k == 0 || k == 2 * s.V) return false;  // at the search's edge: no fit
  const double cm = prof[k - 1], c0 = prof[k], cp = prof[k + 1];
  const double denom = cm - 2 * c0 + cp;
  if (!(denom > 0)) return false;
  offset = (k - s.V) + 0.5 * (cm - cp) / denom;
  return true;
}

float median_of(std::span<float> v) {
  auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

}  // namespace

Status validate(const CalibCheckParams& p) {
  if (p.max_features < 16 || p.max_features > 4096)
    return Error::make(Errc::invalid_argument, "calib check: max_features %d not in 16..4096",
                       p.max_features);
  if (p.patch_radius < 1 || p.patch_radius > 7)
    return Error::make(Errc::invalid_argument, "calib check: patch_radius %d not in 1..7",
                       p.patch_radius);
  if (p.vertical_search_px < 1 || p.vertical_search_px > 8)
    return Error::make(Errc::invalid_argument, "calib check: vertical_search_px %d not in 1..8",
                       p.vertical_search_px);
  if (p.min_corner_score < 0)
    return Error::make(Errc::invalid_argument, "calib check: min_corner_score %d < 0",
                       p.min_corner_score);
  if (!(p.uniqueness > 0 && p.uniqueness <= 1))
    return Error::make(Errc::invalid_argument, "calib check: uniqueness %.3g not in (0, 1]",
                       p.uniqueness);
  if (p.min_features < 1 || p.min_features > p.max_features)
    return Error::make(Errc::invalid_argument, "calib check: min_features %d not in 1..%d",
                       p.min_features, p.max_features);
  if (!(p.drift_px > 0 && p.drift_px < 8))
    return Error::make(Errc::invalid_argument, "calib check: drift_px %.3g not in (0, 8)",
                       p.drift_px);
  return {};
}

const char* to_string(CalibVerdict v) {
  switch (v) {
    case CalibVerdict::ok:
      return "ok";
    case CalibVerdict::drifted:
      return "drifted";
    case CalibVerdict::corrected:
      return "corrected";
    case CalibVerdict::unknown:
      break;
  }
  return "unknown";
}

std::size_t calib_check_scratch_bytes(const CalibCheckParams& p) {
  return 2 * static_cast<std::size_t>(p.max_features) * sizeof(float) +
         (3 * kMaxDisparities + kMaxPatch) * sizeof(int) + 5 * 64;
}

Result<CalibCheck> check_calibration(ConstGray8View left, ConstGray8View right, Rect left_area,
                                     Rect right_area, int disp_min, int disp_max,
                                     const CalibCheckParams& params, Arena& scratch) {
  PETRA_TRY(validate(params));
  if (left.width() != right.width() || left.height() != right.height())
    return Error::make(Errc::invalid_argument, "calib check: images %dx%d and %dx%d differ",
                       left.width(), left.height(), right.width(), right.height());
  if (!left_area.inside(left.width(), left.height()) ||
      !right_area.inside(right.width(), right.height()))
    return Error::make(Errc::out_of_range, "calib check: an area lies outside the images");
  if (disp_max < disp_min || disp_max - disp_min + 1 > kMaxDisparities)
    return Error::make(Errc::invalid_argument, "calib check: disparity range %d..%d not 1..%d wide",
                       disp_min, disp_max, kMaxDisparities);
  const std::size_t mark = scratch.mark();
  auto offsets =
      scratch.allocate<float>(static_cast<std::size_t>(params.max_features), "calib offsets");
  if (!offsets) return offsets.error();
  auto devs =
      scratch.allocate<float>(static_cast<std::size_t>(params.max_features), "calib deviations");
  if (!devs) return devs.error();
  const auto nd = static_cast<std::size_t>(disp_max - disp_min + 1);
  auto per_d = scratch.allocate<int>(nd, "calib costs");
  if (!per_d) return per_d.error();
  auto sums = scratch.allocate<int>(nd, "calib patch sums");
  if (!sums) return sums.error();
  auto costs = scratch.allocate<int>(nd + kMaxPatch, "calib row costs");
  if (!costs) return costs.error();
  const CostRows rows{*per_d, *sums, *costs};

  const int r = params.patch_radius, V = params.vertical_search_px;
  // Left margin: patch and corner window; rows also leave room for the row search.
  const int mx = std::max(r, kScoreRadius + 1);
  const int top = std::max(left_area.y + mx, right_area.y + r + V);
  const int bottom = std::min(left_area.y + left_area.h - mx, right_area.y + right_area.h - r - V);
  const int x0 = left_area.x + mx, x1 = left_area.x + left_area.w - mx;
  CalibCheck out;
  out.present = true;
  if (x1 <= x0 || bottom <= top) {
    scratch.release_to(mark);
    return out;  // too small an area: unknown
  }
  const int w = x1 - x0, h = bottom - top;
  int cell =
      std::max(1, static_cast<int>(std::ceil(std::sqrt(double(w) * h / params.max_features))));
  while (((w + cell - 1) / cell) * ((h + cell - 1) / cell) > params.max_features) ++cell;

  const Search s{right, right_area, disp_min, disp_max, r, V, params.uniqueness};
  Patch patch;
  int kept = 0;
  for (int cy = top; cy < bottom; cy += cell)
    for (int cx = x0; cx < x1; cx += cell) {
      const Corner c =
          strongest_corner(left, cx, std::min(cx + cell, x1), cy, std::min(cy + cell, bottom));
      if (c.score < params.min_corner_score) continue;
      ++out.candidates;
      load_patch(left, c.x, c.y, r, patch);
      double off = 0;
      if (match_feature(s, patch, c.x, c.y, rows, off))
        (*offsets)[static_cast<std::size_t>(kept++)] = static_cast<float>(off);
    }
  out.features = kept;
  if (kept > 0) {
    std::span<float> v = offsets->first(static_cast<std::size_t>(kept));
    const float med = median_of(v);
    std::span<float> dv = devs->first(static_cast<std::size_t>(kept));
    for (std::size_t i = 0; i < v.size(); ++i) dv[i] = std::fabs(v[i] - med);
    out.vertical_offset_px = static_cast<double>(med);
    out.spread_px = 1.4826 * static_cast<double>(median_of(dv));
  }
  if (kept < params.min_features)
    out.verdict = CalibVerdict::unknown;
  else
    out.verdict = std::fabs(out.vertical_offset_px) > params.drift_px ? CalibVerdict::drifted
                                                                      : CalibVerdict::ok;
  scratch.release_to(mark);
  return out;
}

}  // namespace petra
