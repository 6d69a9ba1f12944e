#include "algo/stereo/canny.hpp"

#include <algorithm>
#include <bit>
#include <cstdlib>
#include <cstring>

#include "algo/stereo/padded_row.hpp"
#include "algo/stereo/vector_clones.hpp"

namespace petra {

namespace {

constexpr std::uint8_t kWeak = 0x20;  // candidate during hysteresis only

// Sector boundaries: |gy|/|gx| <= 13/32 (tan 22.1 deg) is horizontal,
// >= 32/13 (tan 67.9 deg) vertical; 16-bit products keep the test in vector
// lanes (|g| <= 1020).
constexpr int kTanNum = 13;
constexpr int kTanDen = 32;

// The row kernels are out of line: inlined into canny() they are not
// vectorised by GCC 12.
PETRA_VECTOR_CLONES [[gnu::noinline]] void vertical_binomial(const std::uint16_t* __restrict a,
                                                             const std::uint16_t* __restrict b,
                                                             const std::uint16_t* __restrict c,
                                                             const std::uint16_t* __restrict d,
                                                             const std::uint16_t* __restrict e,
                                                             int n, std::uint8_t* __restrict o) {
  for (int i = 0; i < n; ++i)
    o[i] = static_cast<std::uint8_t>((a[i] + 4 * b[i] + 6 * c[i] + 4 * d[i] + e[i] + 128) >> 8);
}

// Horizontal [1 4 6 4 1] of one padded row: out[i] from s[i .. i + 4].
PETRA_VECTOR_CLONES [[gnu::noinline]] void horizontal_binomial(const std::uint8_t* __restrict s,
                                                               int n,
                                                               std::uint16_t* __restrict out) {
  for (int i = 0; i < n; ++i)
    out[i] =
        static_cast<std::uint16_t>(s[i] + 4 * s[i + 1] + 6 * s[i + 2] + 4 * s[i + 3] + s[i + 4]);
}

// Sobel gradients and L1 magnitude of one row from three smoothed rows.
PETRA_VECTOR_CLONES [[gnu::noinline]] void sobel_row(const std::uint8_t* __restrict up,
                                                     const std::uint8_t* __restrict mid,
                                                     const std::uint8_t* __restrict dn, int n,
                                                     std::int16_t* __restrict ox,
                                                     std::int16_t* __restrict oy,
                                                     std::uint16_t* __restrict om) {
  for (int i = 0; i < n; ++i) {
    const int vx = (up[i + 2] + 2 * mid[i + 2] + dn[i + 2]) - (up[i] + 2 * mid[i] + dn[i]);
    const int vy = (dn[i] + 2 * dn[i + 1] + dn[i + 2]) - (up[i] + 2 * up[i + 1] + up[i + 2]);
    ox[i] = static_cast<std::int16_t>(vx);
    oy[i] = static_cast<std::int16_t>(vy);
    om[i] = static_cast<std::uint16_t>((vx < 0 ? -vx : vx) + (vy < 0 ? -vy : vy));
  }
}

// Non-maximum suppression of one row. up/mid/dn are the magnitude rows
// above, at and below, offset so that index i is the pixel's column
// (i - 1 and i + 1 are valid). Writes 0, or the sector and sign with kWeak
// or kEdgeBit. Branch-free so the compiler runs it in vector lanes.
PETRA_VECTOR_CLONES [[gnu::noinline]] void nms_row(
    const std::int16_t* __restrict gx, const std::int16_t* __restrict gy,
    const std::uint16_t* __restrict up, const std::uint16_t* __restrict mid,
    const std::uint16_t* __restrict dn, int w, int low, int high, std::uint8_t* __restrict out) {
  const std::int16_t lo = static_cast<std::int16_t>(low), hi = static_cast<std::int16_t>(high);
  // Every neighbour is loaded and chosen by masks: a select between two
  // addresses would be a gather, which stops the vectoriser.
  auto pick = [](std::int16_t mask, std::int16_t a, std::int16_t b) {
    return static_cast<std::int16_t>((a & mask) | (b & ~mask));
  };
  for (int i = 0; i < w; ++i) {
    const std::int16_t m = static_cast<std::int16_t>(mid[i]);
    const std::int16_t l = static_cast<std::int16_t>(mid[i - 1]),
                       r = static_cast<std::int16_t>(mid[i + 1]);
    const std::int16_t u = static_cast<std::int16_t>(up[i]), d = static_cast<std::int16_t>(dn[i]);
    const std::int16_t ul = static_cast<std::int16_t>(up[i - 1]),
                       ur = static_cast<std::int16_t>(up[i + 1]);
    const std::int16_t dl = static_cast<std::int16_t>(dn[i - 1]),
                       dr = static_cast<std::int16_t>(dn[i + 1]);
    const std::int16_t ax = static_cast<std::int16_t>(gx[i] < 0 ? -gx[i] : gx[i]);
    const std::int16_t ay = static_cast<std::int16_t>(gy[i] < 0 ? -gy[i] : gy[i]);
    const std::int16_t horizontal = static_cast<std::int16_t>(-(ay * kTanDen <= ax * kTanNum));
    const std::int16_t vertical = static_cast<std::int16_t>(-(ay * kTanNum >= ax * kTanDen));
    const std::int16_t same = static_cast<std::int16_t>(-((gx[i] > 0) == (gy[i] > 0)));
    const std::int16_t n1 = pick(horizontal, l, pick(vertical, u, pick(same, ul, ur)));
    const std::int16_t n2 = pick(horizontal, r, pick(vertical, d, pick(same, dr, dl)));
    const std::int16_t sector =
        pick(horizontal, kSectorHorizontal,
             pick(vertical, kSectorVertical, pick(same, kSectorDiagonal, kSectorAntiDiagonal)));
    // Strict on one side, so a plateau of two equal pixels keeps one.
    const bool keep = m >= lo && m > n1 && m >= n2;
    const int code = sector | (gx[i] < 0 ? kEdgeGxNegative : 0) | (m >= hi ? kEdgeBit : kWeak);
    out[i] = static_cast<std::uint8_t>(keep ? code : 0);
  }
}

// Clears the weak pixels hysteresis left behind; returns the edges of the row.
// Out of line and cloned: inside canny() the loop stayed scalar.
PETRA_VECTOR_CLONES [[gnu::noinline]] int drop_weak_row(std::uint8_t* __restrict row, int w) {
  int n = 0;  // a local count: the vectoriser keeps it in lanes
  for (int i = 0; i < w; ++i) {
    const std::uint8_t v = (row[i] & kWeak) != 0 ? std::uint8_t{0} : row[i];
    row[i] = v;
    n += is_edge(v);
  }
  return n;
}

std::size_t sz(int w, int h) {
  return static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
}

Status check_canny_args(ConstGray8View image, Rect area, const CannyParams& params,
                        Gray8View edges) {
  if (area.empty())
    return Error::make(Errc::invalid_argument, "canny: area %dx%d is empty", area.w, area.h);
  if (!area.inside(image.width(), image.height()))
    return Error::make(Errc::out_of_range, "canny: area (%d,%d %dx%d) outside the %dx%d image",
                       area.x, area.y, area.w, area.h, image.width(), image.height());
  if (edges.width() != area.w || edges.height() != area.h)
    return Error::make(Errc::invalid_argument, "canny: edges are %dx%d, area is %dx%d",
                       edges.width(), edges.height(), area.w, area.h);
  if (params.low <= 0 || params.high < params.low)
    return Error::make(Errc::invalid_argument,
                       "canny: thresholds low %d, high %d (need 0 < low <= high)", params.low,
                       params.high);
  return ok_status();
}

// The scratch of one call. Every buffer is written whole before it is read
// (smoothing, Sobel, the row filters; the stack below its top): no
// value-initialisation.
struct CannyBuffers {
  int w = 0, h = 0;
  int sw = 0, sh = 0;  // smoothed: area grown by 2
  int gw = 0, gh = 0;  // gradients: area grown by 1
  std::span<std::uint8_t> sm, src_row;
  std::span<std::int16_t> gx, gy;
  std::span<std::uint16_t> mag, hring;
  std::span<std::uint32_t> stack;
};

Status allocate_buffers(Arena& scratch, CannyBuffers& b) {
  const int w = b.w, h = b.h, sw = b.sw, sh = b.sh, gw = b.gw, gh = b.gh;
  auto sm_buf = scratch.allocate_uninitialised<std::uint8_t>(sz(sw, sh), "canny smoothed image");
  if (!sm_buf) return sm_buf.error();
  auto gx_buf = scratch.allocate_uninitialised<std::int16_t>(sz(gw, gh), "canny gx");
  if (!gx_buf) return gx_buf.error();
  auto gy_buf = scratch.allocate_uninitialised<std::int16_t>(sz(gw, gh), "canny gy");
  if (!gy_buf) return gy_buf.error();
  auto mag_buf = scratch.allocate_uninitialised<std::uint16_t>(sz(gw, gh), "canny magnitude");
  if (!mag_buf) return mag_buf.error();
  auto stack = scratch.allocate_uninitialised<std::uint32_t>(sz(w, h), "canny stack");
  if (!stack) return stack.error();
  auto src_row =
      scratch.allocate_uninitialised<std::uint8_t>(static_cast<std::size_t>(w) + 8, "canny row");
  if (!src_row) return src_row.error();
  auto hring =
      scratch.allocate_uninitialised<std::uint16_t>(static_cast<std::size_t>(sw) * 5, "canny ring");
  if (!hring) return hring.error();
  b.sm = *sm_buf, b.gx = *gx_buf, b.gy = *gy_buf, b.mag = *mag_buf;
  b.stack = *stack, b.src_row = *src_row, b.hring = *hring;
  return ok_status();
}

// 1. Smoothing, separable binomial [1 4 6 4 1]/16 per axis: horizontal
// rows in a ring of five, then the vertical combination.
void smooth(ConstGray8View image, Rect area, const CannyBuffers& b) {
  const int w = b.w, sw = b.sw, sh = b.sh;
  const ImageView<std::uint8_t> sm = ImageView<std::uint8_t>::over(b.sm, sw, sh);
  auto hfilter = [&](int y_img, std::uint16_t* out) {
    std::uint8_t* s = b.src_row.data();
    padded_row(image, y_img, area.x - 4, w + 8, s);
    horizontal_binomial(s, sw, out);  // out[i] is column area.x - 2 + i
  };
  std::uint16_t* ring = b.hring.data();
  const int y_first = area.y - 4;  // first source row needed
  for (int k = 0; k < 4; ++k) hfilter(y_first + k, ring + (k % 5) * sw);
  for (int r = 0; r < sh; ++r) {
    hfilter(y_first + r + 4, ring + ((r + 4) % 5) * sw);
    const std::uint16_t* a = ring + (r % 5) * sw;
    const std::uint16_t* bb = ring + ((r + 1) % 5) * sw;
    const std::uint16_t* c = ring + ((r + 2) % 5) * sw;
    const std::uint16_t* d = ring + ((r + 3) % 5) * sw;
    const std::uint16_t* e = ring + ((r + 4) % 5) * sw;
    vertical_binomial(a, bb, c, d, e, sw, sm.row(r));
  }
}

// 2. Sobel on the smoothed image.
void sobel(const CannyBuffers& b) {
  const int gw = b.gw, gh = b.gh;
  const ImageView<std::uint8_t> sm = ImageView<std::uint8_t>::over(b.sm, b.sw, b.sh);
  const ImageView<std::int16_t> gx = ImageView<std::int16_t>::over(b.gx, gw, gh);
  const ImageView<std::int16_t> gy = ImageView<std::int16_t>::over(b.gy, gw, gh);
  const ImageView<std::uint16_t> mg = ImageView<std::uint16_t>::over(b.mag, gw, gh);
  for (int j = 0; j < gh; ++j)
    sobel_row(sm.row(j), sm.row(j + 1), sm.row(j + 2), gw, gx.row(j), gy.row(j), mg.row(j));
}

// 3. Non-maximum suppression, one row at a time (nms_row, vectorised);
// then the strong pixels seed the stack. Returns the stack's top.
std::size_t suppress_and_seed(const CannyBuffers& b, const CannyParams& params, int shift,
                              Gray8View edges) {
  const int w = b.w, h = b.h, gw = b.gw, gh = b.gh;
  const ImageView<std::int16_t> gx = ImageView<std::int16_t>::over(b.gx, gw, gh);
  const ImageView<std::int16_t> gy = ImageView<std::int16_t>::over(b.gy, gw, gh);
  const ImageView<std::uint16_t> mg = ImageView<std::uint16_t>::over(b.mag, gw, gh);
  std::size_t top = 0;
  for (int j = 0; j < h; ++j) {
    std::uint8_t* out = edges.row(j);
    nms_row(gx.row(j + 1) + 1, gy.row(j + 1) + 1, mg.row(j) + 1, mg.row(j + 1) + 1,
            mg.row(j + 2) + 1, w, params.low, params.high, out);
    // Branch-free push (the stack holds w h entries, top <= j w + i), eight
    // pixels at a time, skipped when none of them is strong (most are not).
    std::uint32_t* st = b.stack.data();
    int i = 0;
    for (; i + 8 <= w; i += 8) {
      std::uint64_t word;
      std::memcpy(&word, out + i, sizeof word);
      if ((word & (0x0101010101010101ULL * kEdgeBit)) == 0) continue;
      for (int k = 0; k < 8; ++k) {
        st[top] = (static_cast<std::uint32_t>(j) << shift) | static_cast<std::uint32_t>(i + k);
        top += (out[i + k] & kEdgeBit) != 0;
      }
    }
    for (; i < w; ++i) {
      st[top] = (static_cast<std::uint32_t>(j) << shift) | static_cast<std::uint32_t>(i);
      top += (out[i] & kEdgeBit) != 0;
    }
  }
  return top;
}

// 4. Hysteresis: grow strong edges into 8-connected weak pixels. A pixel is
// pushed only when it becomes an edge, so the stack never exceeds w*h.
void hysteresis(std::span<std::uint32_t> stack, std::size_t top, int shift, Gray8View edges) {
  const int w = edges.width(), h = edges.height();
  const std::uint32_t column_mask = (std::uint32_t{1} << shift) - 1;
  const std::size_t capacity = stack.size();
  while (top > 0) {
    const std::uint32_t p = stack[--top];
    const int j = static_cast<int>(p >> shift);
    const int i = static_cast<int>(p & column_mask);
    const int i0 = i > 0 ? i - 1 : 0, i1 = i < w - 1 ? i + 1 : w - 1;
    for (int dj = -1; dj <= 1; ++dj) {
      const int jj = j + dj;
      if (jj < 0 || jj >= h) continue;
      std::uint8_t* row = edges.row(jj);
      // Most neighbourhoods hold no weak pixel: one test for the three
      // (a branch per pixel on data mispredicts), as three loads.
      if (((row[i0] | row[i] | row[i1]) & kWeak) == 0) continue;
      for (int ii = i0; ii <= i1; ++ii) {
        if ((row[ii] & kWeak) == 0) continue;
        row[ii] = static_cast<std::uint8_t>((row[ii] & ~kWeak) | kEdgeBit);
        PETRA_ASSERT(top < capacity);
        stack[top++] = (static_cast<std::uint32_t>(jj) << shift) | static_cast<std::uint32_t>(ii);
      }
    }
  }
}

}  // namespace

std::size_t canny_scratch_bytes(int w, int h) {
  if (w <= 0 || h <= 0) return 0;
  return sz(w + 4, h + 4) + 3 * sizeof(std::int16_t) * sz(w + 2, h + 2) +
         sizeof(std::uint32_t) * sz(w, h) + (w + 8) + 2 * sizeof(std::uint16_t) * (w + 4) * 5 +
         7 * kArenaSlackPerAllocation;
}

Result<CannyStats> canny(ConstGray8View image, Rect area, const CannyParams& params, Arena& scratch,
                         Gray8View edges) {
  PETRA_TRY(check_canny_args(image, area, params, edges));
  // The hysteresis stack holds pixels as row << shift | column (w <= 2^shift):
  // no division to unpack them.
  const int shift = std::bit_width(static_cast<unsigned>(area.w - 1));
  if ((static_cast<std::uint64_t>(area.h) << shift) > 0xFFFFFFFFull)
    return Error::make(Errc::capacity_exceeded, "canny: area %dx%d too large", area.w, area.h);
  ArenaScope scope(scratch);
  CannyBuffers b;
  b.w = area.w, b.h = area.h;
  b.sw = b.w + 4, b.sh = b.h + 4;
  b.gw = b.w + 2, b.gh = b.h + 2;
  PETRA_TRY(allocate_buffers(scratch, b));
  smooth(image, area, b);
  sobel(b);
  CannyStats stats;
  const std::size_t top = suppress_and_seed(b, params, shift, edges);
  stats.strong_pixels = static_cast<long>(top);
  hysteresis(b.stack, top, shift, edges);
  for (int j = 0; j < b.h; ++j) stats.edge_pixels += drop_weak_row(edges.row(j), b.w);
  return stats;
}

}  // namespace petra
