// Delaunay triangulation of raster-ordered points (rows of increasing y, x
// increasing within a row), the order disparity maps produce:
//   1. each pair of consecutive rows is zipped into a strip of triangles (two
//      points of one row and one of the other: never degenerate);
//   2. the concave pockets between the strips' left and right ends and the
//      convex hull are filled by a monotone-chain scan (the popped vertex and
//      its two chain neighbours form a triangle);
//   3. Lawson edge flips with the exact in-circle test until every edge is
//      locally Delaunay (a triangulation of the hull whose edges are all
//      locally Delaunay is Delaunay). Grid cells are already Delaunay, so few
//      flips happen.
// Adjacency: strip-internal and row edges are linked as they are made; the
// rest (strip ends, pockets) through a small open-addressing edge table.
#include "algo/mesh/delaunay.hpp"

#include "algo/core/arena.hpp"

namespace petra {

namespace {

struct EdgeSlot {
  std::uint64_t key = 0;  // (min << 32 | max) + 1; 0 = empty
  std::int32_t tri = -1;
  std::int32_t edge = -1;
};

class RasterBuilder {
 public:
  RasterBuilder(std::span<const IntPoint> pts, std::span<MeshTriangle> out, Arena& arena)
      : pts_(pts), tri_(out), arena_(arena) {}

  Result<DelaunayStats> run() {
    const std::size_t n = pts_.size();
    PETRA_TRY(check_not_collinear());
    PETRA_TRY(allocate());
    {
      std::int32_t x0 = pts_[0].x, x1 = x0;
      for (const IntPoint& p : pts_) {
        x0 = p.x < x0 ? p.x : x0;
        x1 = p.x > x1 ? p.x : x1;
      }
      small_ = x1 - x0 < kSmallPredicateSpan && pts_[n - 1].y - pts_[0].y < kSmallPredicateSpan;
    }
    // Rows.
    std::size_t rows = 0;
    for (std::size_t i = 0; i < n; ++i)
      if (i == 0 || pts_[i].y != pts_[i - 1].y) row_start_[rows++] = static_cast<std::int32_t>(i);
    row_start_[rows] = static_cast<std::int32_t>(n);
    // The edge table only ever holds strip ends and pocket edges: O(rows).
    auto table = arena_.allocate<EdgeSlot>(table_capacity(rows), "delaunay edge table");
    if (!table) return table.error();
    table_ = *table;
    for (std::size_t i = 0; i < n; ++i) below_[i] = above_[i] = -1;
    for (std::size_t r = 0; r + 1 < rows; ++r) PETRA_TRY(zip(r));
    // Row edges: the strip above owns (i, i+1) as its bottom edge, the strip below as its top.
    for (std::size_t i = 0; i + 1 < n; ++i) {
      if (above_[i] < 0 || below_[i] < 0) continue;
      link_edge(above_[i], static_cast<std::int32_t>(i), static_cast<std::int32_t>(i + 1),
                below_[i]);
    }
    PETRA_TRY(fill_pockets(rows, true));
    PETRA_TRY(fill_pockets(rows, false));
    PETRA_TRY(link_remaining());
    flip_all();
    DelaunayStats stats;
    stats.triangles = count_;
    stats.vertices = n;
    for (std::size_t t = 0; t < count_; ++t)
      for (int k = 0; k < 3; ++k) stats.hull_edges += tri_[t].n[k] < 0;
    stats.walk_steps = flips_;  // no walk here: report the flips instead
    return stats;
  }

 private:
  const IntPoint& P(std::int32_t i) const { return pts_[static_cast<std::size_t>(i)]; }

  Status check_not_collinear() const {
    const std::size_t n = pts_.size();
    // Raster order has no duplicates, so points 0 and 1 differ.
    for (std::size_t i = 2; i < n; ++i)
      if (orient2d(pts_[0], pts_[1], pts_[i]) != 0) return {};
    return Error::make(Errc::degenerate, "delaunay: all %zu points are collinear", n);
  }

  Status allocate() {
    const std::size_t n = pts_.size();
    auto rs = arena_.allocate<std::int32_t>(n + 1, "delaunay rows");
    if (!rs) return rs.error();
    auto below = arena_.allocate<std::int32_t>(n, "delaunay row edges below");
    if (!below) return below.error();
    auto above = arena_.allocate<std::int32_t>(n, "delaunay row edges above");
    if (!above) return above.error();
    auto chain = arena_.allocate<std::int32_t>(n, "delaunay hull chain");
    if (!chain) return chain.error();
    auto stack = arena_.allocate<std::int64_t>(flip_capacity(n), "delaunay flip stack");
    if (!stack) return stack.error();
    row_start_ = *rs;
    below_ = *below;
    above_ = *above;
    chain_ = *chain;
    stack_ = *stack;
    return {};
  }

 public:
  static std::size_t flip_capacity(std::size_t n) { return n + 64; }
  // Edges left unlinked by the strips: two strip ends per row pair and three
  // per pocket triangle (at most two per row): < 10 per row; load <= 1/2.
  static std::size_t table_capacity(std::size_t rows) {
    std::size_t cap = 64;
    while (cap < 20 * rows + 64) cap <<= 1;
    return cap;
  }

 private:
  Result<std::int32_t> add(std::int32_t a, std::int32_t b, std::int32_t c) {
    if (count_ >= tri_.size())
      return Error::make(Errc::capacity_exceeded, "delaunay: more than %zu triangles", tri_.size());
    PETRA_ASSERT(orient2d(P(a), P(b), P(c)) > 0);
    tri_[count_] = MeshTriangle{{a, b, c}, {-1, -1, -1}};
    return static_cast<std::int32_t>(count_++);
  }

  // Index of the edge (u, v) in triangle t (the vertex opposite it).
  int edge_index(std::int32_t t, std::int32_t u, std::int32_t v) const {
    const MeshTriangle& m = tri_[static_cast<std::size_t>(t)];
    for (int k = 0; k < 3; ++k)
      if (m.v[k] != u && m.v[k] != v) return k;
    return -1;
  }
  void link_edge(std::int32_t t1, std::int32_t u, std::int32_t v, std::int32_t t2) {
    const int e1 = edge_index(t1, u, v), e2 = edge_index(t2, u, v);
    tri_[static_cast<std::size_t>(t1)].n[e1] = t2;
    tri_[static_cast<std::size_t>(t2)].n[e2] = t1;
  }

  // Strip between rows r (above, smaller y) and r + 1.
  Status zip(std::size_t r) {
    std::int32_t i = row_start_[r], i_end = row_start_[r + 1];
    std::int32_t j = row_start_[r + 1], j_end = row_start_[r + 2];
    std::int32_t prev = -1;  // previous triangle: shares the diagonal (i, j)
    while (i + 1 < i_end || j + 1 < j_end) {
      const bool advance_a = j + 1 >= j_end || (i + 1 < i_end && P(i + 1).x <= P(j + 1).x);
      Result<std::int32_t> t = advance_a ? add(i, i + 1, j) : add(i, j + 1, j);
      if (!t) return t.error();
      if (prev >= 0) link_edge(*t, i, j, prev);
      if (advance_a) {
        below_[static_cast<std::size_t>(i)] = *t;  // owns row edge (i, i+1) from below
        ++i;
      } else {
        above_[static_cast<std::size_t>(j)] = *t;  // owns row edge (j, j+1) from above
        ++j;
      }
      prev = *t;
    }
    return {};
  }

  // Monotone-chain scan of the rows' first (left) or last (right) points.
  Status fill_pockets(std::size_t rows, bool left) {
    std::size_t top = 0;
    for (std::size_t r = 0; r < rows; ++r) {
      const std::int32_t q = left ? row_start_[r] : row_start_[r + 1] - 1;
      while (top >= 2) {
        const std::int32_t a = chain_[top - 2], b = chain_[top - 1];
        const std::int64_t o = orient2d(P(a), P(b), P(q));
        if (left ? o <= 0 : o >= 0) break;
        auto t = left ? add(a, b, q) : add(a, q, b);
        if (!t) return t.error();
        --top;
      }
      chain_[top++] = q;
    }
    return {};
  }

  static std::uint64_t key_of(std::int32_t u, std::int32_t v) {
    const std::uint64_t lo = static_cast<std::uint32_t>(u < v ? u : v);
    const std::uint64_t hi = static_cast<std::uint32_t>(u < v ? v : u);
    return ((lo << 32) | hi) + 1;
  }

  // Pairs every still-unlinked edge with its twin through the edge table.
  Status link_remaining() {
    const std::size_t mask = table_.size() - 1;
    std::size_t used = 0;
    for (std::size_t t = 0; t < count_; ++t)
      for (int k = 0; k < 3; ++k) {
        MeshTriangle& m = tri_[t];
        if (m.n[k] >= 0) continue;
        const std::int32_t u = m.v[(k + 1) % 3], v = m.v[(k + 2) % 3];
        // Row edges of the top and bottom rows stay hull edges: skip the table.
        if (P(u).y == P(v).y) continue;
        const std::uint64_t key = key_of(u, v);
        std::size_t h = static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ull) >> 20) & mask;
        for (;;) {
          EdgeSlot& s = table_[h];
          if (s.key == 0) {
            if (++used * 2 > table_.size())
              return Error::make(Errc::capacity_exceeded, "delaunay: edge table full");
            s = EdgeSlot{key, static_cast<std::int32_t>(t), k};
            break;
          }
          if (s.key == key) {
            m.n[k] = s.tri;
            tri_[static_cast<std::size_t>(s.tri)].n[s.edge] = static_cast<std::int32_t>(t);
            break;
          }
          h = (h + 1) & mask;
        }
      }
    return {};
  }

  // Lawson flips from a stack of (triangle, edge); a full sweep takes over
  // if the stack ever fills (never seen: grids need few flips).
  void flip_all() {
    std::size_t sp = 0;
    auto push = [&](std::size_t t, int e) {
      if (sp < stack_.size()) {
        stack_[sp++] = static_cast<std::int64_t>(t) * 4 + e;
      } else {
        overflow_ = true;
      }
    };
    auto drain = [&] {
      while (sp > 0) {
        const std::int64_t top = stack_[--sp];
        flip_if_needed(static_cast<std::size_t>(top / 4), static_cast<int>(top % 4), push);
      }
    };
    // Every edge once (from its lower-numbered triangle); a flip pushes the
    // four edges around it, drained at once so the stack stays short.
    for (std::size_t t = 0; t < count_; ++t)
      for (int e = 0; e < 3; ++e)
        if (tri_[t].n[e] > static_cast<std::int32_t>(t)) {
          flip_if_needed(t, e, push);
          drain();
        }
    while (overflow_) {
      overflow_ = false;
      for (std::size_t t = 0; t < count_; ++t)
        for (int e = 0; e < 3; ++e) {
          flip_if_needed(t, e, push);
          drain();
        }
    }
  }

  template <class Push>
  void flip_if_needed(std::size_t ti, int i, Push& push) {
    MeshTriangle& t = tri_[ti];
    const std::int32_t ui = t.n[i];
    if (ui < 0) return;
    MeshTriangle& u = tri_[static_cast<std::size_t>(ui)];
    const int j = u.n[0] == static_cast<std::int32_t>(ti)
                      ? 0
                      : (u.n[1] == static_cast<std::int32_t>(ti) ? 1 : 2);
    const std::int32_t a = t.v[i], b = t.v[(i + 1) % 3], c = t.v[(i + 2) % 3];
    const std::int32_t w = u.v[j];
    const int inside = small_ ? incircle_sign_small(P(a), P(b), P(c), P(w))
                              : incircle_sign(P(a), P(b), P(c), P(w));
    if (inside <= 0) return;
    // Quad a, b, w, c (counter-clockwise): replace diagonal b-c by a-w.
    const std::int32_t t_ab = t.n[(i + 2) % 3], t_ca = t.n[(i + 1) % 3];
    const std::int32_t u_wc = u.n[(j + 2) % 3], u_bw = u.n[(j + 1) % 3];
    const std::int32_t tid = static_cast<std::int32_t>(ti);
    t = MeshTriangle{{a, b, w}, {u_bw, ui, t_ab}};
    u = MeshTriangle{{a, w, c}, {u_wc, t_ca, tid}};
    if (u_bw >= 0) relink(u_bw, ui, tid);
    if (t_ca >= 0) relink(t_ca, tid, ui);
    ++flips_;
    push(ti, 0);
    push(ti, 2);
    push(static_cast<std::size_t>(ui), 0);
    push(static_cast<std::size_t>(ui), 1);
  }

  void relink(std::int32_t t, std::int32_t from, std::int32_t to) {
    MeshTriangle& m = tri_[static_cast<std::size_t>(t)];
    for (int k = 0; k < 3; ++k)
      if (m.n[k] == from) m.n[k] = to;
  }

  std::span<const IntPoint> pts_;
  std::span<MeshTriangle> tri_;
  Arena& arena_;
  std::span<std::int32_t> row_start_, below_, above_, chain_;
  std::span<std::int64_t> stack_;
  std::span<EdgeSlot> table_;
  std::size_t count_ = 0;
  std::size_t flips_ = 0;
  bool overflow_ = false;
  bool small_ = false;  // coordinates span < 2^14: 64-bit in-circle test is exact
};

}  // namespace

bool is_raster_ordered(std::span<const IntPoint> points) {
  for (std::size_t i = 1; i < points.size(); ++i) {
    const IntPoint& a = points[i - 1];
    const IntPoint& b = points[i];
    if (!(b.y > a.y || (b.y == a.y && b.x > a.x))) return false;
  }
  return true;
}

std::size_t delaunay_raster_scratch_bytes(std::size_t n) {
  return delaunay_raster_scratch_bytes(n, n);  // worst case: one point a row
}

std::size_t delaunay_raster_scratch_bytes(std::size_t n, std::size_t max_rows) {
  return 4 * arena_bytes_for<std::int32_t>(n + 1) +
         arena_bytes_for<std::int64_t>(RasterBuilder::flip_capacity(n)) +
         arena_bytes_for<EdgeSlot>(RasterBuilder::table_capacity(max_rows < n ? max_rows : n));
}

Result<DelaunayStats> delaunay_triangulate_raster(std::span<const IntPoint> points,
                                                  std::span<MeshTriangle> triangles,
                                                  Arena& scratch) {
  PETRA_TRY(check_delaunay_input(points));
  if (!is_raster_ordered(points))
    return Error::make(Errc::invalid_argument, "delaunay: points are not in raster order");
  ArenaScope scope(scratch);
  RasterBuilder builder(points, triangles, scratch);
  return builder.run();
}

}  // namespace petra
