#include "algo/stereo/edge_pairs.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "algo/stereo/canny.hpp"

namespace petra::match {

namespace {

constexpr int kWin = 2 * kZnccRadius + 1;
constexpr int kN = kWin * kWin;
// Windows whose variance (times kN^2) is below this carry no texture: a
// standard deviation under 1.5 gray levels.
constexpr long kMinVariance = static_cast<long>(kN) * kN * 9 / 4;

// Window pixels padded with zeros to a whole 32-byte vector, so the cross
// term is one vector loop with no tail (the zeros add nothing).
constexpr int kPadded = 32;
static_assert(kN <= kPadded, "5x5 window");

struct Window {
  // No alignas: the arena aligns to alignof(T) from the start of the
  // caller's block, whose own alignment it does not know.
  std::uint8_t px[kPadded];
  long sum;
  long var;   // kN * sum(p^2) - sum(p)^2
  double sd;  // sqrt(var), once per window instead of once per pair
};

inline void gather_window(ConstGray8View img, int x, int y, Window& w) {
  int n = 0;
  if (x >= kZnccRadius && x < img.width() - kZnccRadius) {  // no column clamping
    for (int dy = -kZnccRadius; dy <= kZnccRadius; ++dy) {
      const std::uint8_t* row = img.row(std::clamp(y + dy, 0, img.height() - 1)) + x;
      for (int dx = -kZnccRadius; dx <= kZnccRadius; ++dx) w.px[n++] = row[dx];
    }
  } else {
    for (int dy = -kZnccRadius; dy <= kZnccRadius; ++dy) {
      const std::uint8_t* row = img.row(std::clamp(y + dy, 0, img.height() - 1));
      for (int dx = -kZnccRadius; dx <= kZnccRadius; ++dx)
        w.px[n++] = row[std::clamp(x + dx, 0, img.width() - 1)];
    }
  }
  for (int i = kN; i < kPadded; ++i) w.px[i] = 0;
}

// Sums of a gathered window. Apart from the gathering: run right after it,
// the vector loads of px waited for its 32 byte stores to reach the cache
// (a load spanning several stores is not forwarded from them); one pass of
// gathering, then one of sums, puts a whole list of windows between the two.
inline void window_stats(Window& w) {
  int s = 0, ss = 0;  // at most 25 * 255^2; over the padded vector (zeros add nothing)
  for (int i = 0; i < kPadded; ++i) {
    s += w.px[i];
    ss += w.px[i] * w.px[i];
  }
  w.sum = s;
  w.var = kN * static_cast<long>(ss) - static_cast<long>(s) * s;
  w.sd = std::sqrt(static_cast<double>(w.var));
}

int zncc(const Window& a, const Window& b) {
  if (a.var < kMinVariance || b.var < kMinVariance) return 0;
  int cross = 0;  // at most 25 * 255^2: an int, which vectorises as 16-bit products
  for (int i = 0; i < kPadded; ++i) cross += a.px[i] * b.px[i];
  const long num = kN * static_cast<long>(cross) - a.sum * b.sum;
  // var products stay below 2^50: the product of the roots is exact enough.
  // Rounded inline: for 1 <= v < 2^52, v + 0.5 is exact and truncation
  // gives lround(v) (a library call per pair otherwise).
  const double v = a.sd * b.sd;
  const long den = static_cast<long>(v + 0.5);  // NOLINT(bugprone-incorrect-roundings): see above
  if (den <= 0) return 0;
  // The quotient in double: |num * kZnccOne| < 2^36 and den are exact, and
  // a non-integer quotient lies at least 1 / den from an integer, more than
  // its rounding error, so truncation gives the integer division's result
  // (a 64-bit integer division per pair was the costlier instruction).
  return static_cast<int>(static_cast<double>(num * kZnccOne) / static_cast<double>(den));
}

// A usable edge has a position along the row: not a horizontal edge.
int usable(std::uint8_t code) {  // & not &&: no branch in the list compaction
  return static_cast<int>(is_edge(code)) & static_cast<int>(edge_sector(code) != kSectorVertical);
}

// Columns x0 + i of the usable edges among codes[0..count) into list (count
// entries); returns how many. Branch-free compaction (whether a pixel is an
// edge is data, and a branch on it mispredicts; the unconditional store stays
// inside the list), eight codes at a time tested as one word and skipped
// when none is usable (most are not edges).
int compact_usable(const std::uint8_t* codes, int count, int x0, std::int16_t* list) {
  constexpr std::uint64_t kOnes = 0x0101010101010101ULL;
  static_assert(kEdgeBit == 0x80 && kEdgeSectorMask == 0x03 && kSectorVertical == 2,
                "the word test below reads these bits");
  int m = 0, i = 0;
  for (; i + 8 <= count; i += 8) {
    std::uint64_t word;
    std::memcpy(&word, codes + i, sizeof word);
    // Per byte: bit 7 = edge, and sector 2 (bits 1..0 = 10) = horizontal edge.
    const std::uint64_t horizontal = (word >> 1) & ~word & kOnes;
    const std::uint64_t ok = word & (kOnes * kEdgeBit) & ~(horizontal << 7);
    if (ok == 0) continue;
    for (int b = 0; b < 8; ++b) {
      list[m] = static_cast<std::int16_t>(x0 + i + b);
      m += static_cast<int>((ok >> (8 * b + 7)) & 1);
    }
  }
  for (; i < count; ++i) {
    list[m] = static_cast<std::int16_t>(x0 + i);
    m += usable(codes[i]);
  }
  return m;
}

enum : std::uint8_t { kFromUp = 0, kFromLeft = 1, kMatch = 2 };

// The usable edges of both rows (columns, in order) and their windows.
struct EdgeLists {
  std::int16_t* lx = nullptr;
  std::int16_t* rx = nullptr;
  Window* lw = nullptr;
  Window* rw = nullptr;
  int m = 0, n = 0;  // left, right edges
};

// Scratch written before it is read, so not value-initialised: the lists up
// to their counts, the windows whole. Leaves m or n 0 (no windows) when a row
// has no usable edge.
Status edge_lists(const EdgeRowInputs& in, Arena& arena, EdgeLists& e) {
  auto lx = arena.allocate_uninitialised<std::int16_t>(static_cast<std::size_t>(in.left_n),
                                                       "edge list left");
  if (!lx) return lx.error();
  auto rx = arena.allocate_uninitialised<std::int16_t>(static_cast<std::size_t>(in.right_n),
                                                       "edge list right");
  if (!rx) return rx.error();
  e.lx = lx->data();
  e.rx = rx->data();
  const int m = e.m = compact_usable(in.left_edges, in.left_n, in.left_x0, e.lx);
  const int n = e.n = compact_usable(in.right_edges, in.right_n, in.right_x0, e.rx);
  if (m == 0 || n == 0) return ok_status();

  auto lw = arena.allocate_uninitialised<Window>(static_cast<std::size_t>(m), "edge windows left");
  if (!lw) return lw.error();
  auto rw = arena.allocate_uninitialised<Window>(static_cast<std::size_t>(n), "edge windows right");
  if (!rw) return rw.error();
  e.lw = lw->data();
  e.rw = rw->data();
  for (int i = 0; i < m; ++i) gather_window(in.left, e.lx[i], in.y, e.lw[i]);
  for (int j = 0; j < n; ++j) gather_window(in.right, e.rx[j], in.y, e.rw[j]);
  for (int i = 0; i < m; ++i) window_stats(e.lw[i]);
  for (int j = 0; j < n; ++j) window_stats(e.rw[j]);
  return ok_status();
}

// Row i of F and of the backtrack table (brow), from row i - 1 (prev), with
// the right edges of left edge i's disparity range in [j0, j1).
[[gnu::always_inline]] inline void pair_table_row(const EdgeRowInputs& in, const EdgeLists& e,
                                                  int i, int j0, int j1, const std::int32_t* prev,
                                                  std::int32_t* cur, std::int32_t* score,
                                                  std::uint8_t* brow) {
  const int n = e.n;
  const std::uint8_t gl = in.left_edges[e.lx[i - 1] - in.left_x0] & kEdgeGxNegative;
  cur[0] = 0;
  // Before the run: F(i, j) = F(i - 1, j), since F(i, j - 1) = F(i - 1, j - 1)
  // <= F(i - 1, j) (F never decreases along j), and ties go up.
  for (int j = 1; j < j0; ++j) {
    cur[j] = prev[j];
    brow[j] = kFromUp;
  }
  // Scores of the run first: each ZNCC (a division) is independent of the
  // others, where inside the recurrence each waited for the previous cell.
  // A pair needs the same gradient sign and ZNCC >= the floor; it scores
  // ZNCC - floor + 1 (+1: a pair at the floor still counts), else -1.
  for (int j = j0; j < j1; ++j) {
    const int xr = e.rx[j - 1];
    int z = -1;
    if ((in.right_edges[xr - in.right_x0] & kEdgeGxNegative) == gl) {
      const int c = zncc(e.lw[i - 1], e.rw[j - 1]);
      if (c >= in.zncc_floor_q10) z = c - in.zncc_floor_q10 + 1;
    }
    score[j] = z;
  }
  // The cells without branches (which predecessor wins is data).
  for (int j = j0; j < j1; ++j) {
    const std::int32_t up = prev[j], left = cur[j - 1], diag = prev[j - 1] + score[j];
    const bool from_left = left > up;
    const std::int32_t b1 = from_left ? left : up;
    const bool match = (score[j] >= 0) & (diag > b1);
    cur[j] = match ? diag : b1;
    brow[j] = match ? kMatch : (from_left ? kFromLeft : kFromUp);
  }
  // After the run: the better of the two predecessors, as a running value.
  std::int32_t run = cur[j1 - 1];
  for (int j = j1; j <= n; ++j) {
    const bool left = run > prev[j];
    run = left ? run : prev[j];
    cur[j] = run;
    brow[j] = left ? kFromLeft : kFromUp;
  }
}

// F(i, j): best score pairing the first i left and first j right edges in
// order. O(m n) per row; only pairs within the disparity range are scored.
// Right edges are sorted by x, so those within the disparity range of a
// left edge are one run [j0, j1) of the list, moving right with i. Outside
// it a cell only carries the best of its two predecessors. Fills back
// ((m + 1) x (n + 1): rows 1..m at columns 1..n, all the backtrack reads).
Status fill_pair_table(const EdgeRowInputs& in, const EdgeLists& e, Arena& arena,
                       std::uint8_t* back) {
  const int m = e.m, n = e.n;
  const std::size_t cols = static_cast<std::size_t>(n) + 1;
  auto f = arena.allocate_uninitialised<std::int32_t>(2 * cols, "edge DP rows");
  if (!f) return f.error();
  std::int32_t* prev = f->data();
  std::int32_t* cur = f->data() + cols;
  auto zs = arena.allocate_uninitialised<std::int32_t>(cols, "edge pair scores");
  if (!zs) return zs.error();
  std::int32_t* score = zs->data();
  std::fill(prev, prev + cols, 0);
  int j0 = 1, j1 = 1;  // 1-based, [j0, j1)
  for (int i = 1; i <= m; ++i) {
    const int xl = e.lx[i - 1];
    while (j0 <= n && xl - e.rx[j0 - 1] > in.disp_max) ++j0;
    j1 = std::max(j1, j0);
    while (j1 <= n && xl - e.rx[j1 - 1] >= in.disp_min) ++j1;
    pair_table_row(in, e, i, j0, j1, prev, cur, score, back + static_cast<std::size_t>(i) * cols);
    std::swap(prev, cur);
  }
  return ok_status();
}

// Backtrack from (m, n); pairs come out right to left, then are reversed.
Result<int> backtrack_pairs(const EdgeRowInputs& in, const EdgeLists& e, const std::uint8_t* back,
                            std::span<EdgePair> pairs) {
  const std::size_t cols = static_cast<std::size_t>(e.n) + 1;
  int count = 0;
  int i = e.m, j = e.n;
  while (i > 0 && j > 0) {
    const std::uint8_t from = back[static_cast<std::size_t>(i) * cols + j];
    if (from == kMatch) {
      if (count >= static_cast<int>(pairs.size()))
        return Error::make(Errc::capacity_exceeded, "edge pairs: more than %zu pairs on row %d",
                           pairs.size(), in.y);
      EdgePair p;
      p.x_left = e.lx[i - 1];
      p.x_right = e.rx[j - 1];
      p.zncc_q10 = static_cast<std::int16_t>(zncc(e.lw[i - 1], e.rw[j - 1]));
      pairs[static_cast<std::size_t>(count++)] = p;
      --i;
      --j;
    } else if (from == kFromUp) {
      --i;
    } else {
      --j;
    }
  }
  std::reverse(pairs.begin(), pairs.begin() + count);
  return count;
}

}  // namespace

int zncc_q10(ConstGray8View left, int xl, ConstGray8View right, int xr, int y) {
  Window a, b;
  gather_window(left, xl, y, a);
  gather_window(right, xr, y, b);
  window_stats(a);
  window_stats(b);
  return zncc(a, b);
}

std::size_t edge_row_scratch_bytes(int left_n, int right_n) {
  const std::size_t m = static_cast<std::size_t>(std::max(left_n, 0));
  const std::size_t n = static_cast<std::size_t>(std::max(right_n, 0));
  return (m + 1) * (n + 1) + (m + n) * (sizeof(Window) + sizeof(std::int16_t)) +
         3 * (n + 1) * sizeof(std::int32_t) + 7 * kArenaSlackPerAllocation;
}

Result<int> match_edge_row(const EdgeRowInputs& in, Arena& arena, std::span<EdgePair> pairs) {
  ArenaScope scope(arena);
  EdgeLists e;
  PETRA_TRY(edge_lists(in, arena, e));
  if (e.m == 0 || e.n == 0) return 0;
  const std::size_t cols = static_cast<std::size_t>(e.n) + 1;
  auto back = arena.allocate_uninitialised<std::uint8_t>((static_cast<std::size_t>(e.m) + 1) * cols,
                                                         "edge DP table");
  if (!back) return back.error();
  PETRA_TRY(fill_pair_table(in, e, arena, back->data()));
  return backtrack_pairs(in, e, back->data(), pairs);
}

}  // namespace petra::match
