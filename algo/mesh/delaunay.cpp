#include "algo/mesh/delaunay.hpp"

#include "algo/core/arena.hpp"

namespace petra {

namespace {

constexpr std::int32_t kGhost = -1;  // the vertex at infinity
constexpr std::int32_t kDead = -2;   // v[0] of a free pool slot

struct Boundary {
  std::int32_t a, b;        // cavity edge a -> b (cavity on its left)
  std::int32_t outside;     // triangle beyond it
  std::int32_t outside_at;  // index in outside.n that points into the cavity
};

std::size_t pool_capacity(std::size_t n) {
  return 2 * n + 8;
}

constexpr int kRounds = 8;     // BRIO rounds
constexpr int kRoundBits = 3;  // bits to hold a round number

// Hilbert index of (x, y) on a 2^bits grid (iterative, no recursion).
std::uint64_t hilbert_key(std::uint32_t x, std::uint32_t y, int bits) {
  std::uint64_t d = 0;
  for (int level = bits - 1; level >= 0; --level) {
    const std::uint32_t s = 1u << level;
    const std::uint32_t rx = (x & s) ? 1u : 0u;
    const std::uint32_t ry = (y & s) ? 1u : 0u;
    d += static_cast<std::uint64_t>(s) * s * ((3u * rx) ^ ry);
    x &= s - 1;
    y &= s - 1;
    if (ry == 0) {
      if (rx == 1) {
        x = s - 1 - x;
        y = s - 1 - y;
      }
      const std::uint32_t t = x;
      x = y;
      y = t;
    }
  }
  return d;
}

class Builder {
 public:
  Builder(std::span<const IntPoint> pts, Arena& arena) : pts_(pts), arena_(arena) {}

  Status allocate() {
    const std::size_t n = pts_.size();
    const std::size_t cap = pool_capacity(n);
    auto pool = arena_.allocate<MeshTriangle>(cap, "delaunay triangle pool");
    if (!pool) return pool.error();
    auto mark = arena_.allocate<std::uint32_t>(cap, "delaunay marks");
    if (!mark) return mark.error();
    auto stack = arena_.allocate<std::int32_t>(cap, "delaunay stack");
    if (!stack) return stack.error();
    auto cavity = arena_.allocate<std::int32_t>(cap, "delaunay cavity");
    if (!cavity) return cavity.error();
    auto boundary = arena_.allocate<Boundary>(cap, "delaunay boundary");
    if (!boundary) return boundary.error();
    auto link = arena_.allocate<std::int32_t>(n + 1, "delaunay links");
    if (!link) return link.error();
    auto keys = arena_.allocate<std::uint64_t>(2 * n, "delaunay sort keys");
    if (!keys) return keys.error();
    auto order = arena_.allocate<std::uint32_t>(2 * n, "delaunay order");
    if (!order) return order.error();
    pool_ = *pool;
    mark_ = *mark;
    stack_ = *stack;
    cavity_ = *cavity;
    boundary_ = *boundary;
    link_ = *link;
    keys_ = *keys;
    order_ = *order;
    return {};
  }

  void sort_hilbert() {
    const std::size_t n = pts_.size();
    std::int32_t minx = pts_[0].x, miny = pts_[0].y, maxx = minx, maxy = miny;
    for (const IntPoint& p : pts_) {
      minx = p.x < minx ? p.x : minx;
      miny = p.y < miny ? p.y : miny;
      maxx = p.x > maxx ? p.x : maxx;
      maxy = p.y > maxy ? p.y : maxy;
    }
    const std::uint32_t span =
        static_cast<std::uint32_t>((maxx - minx) > (maxy - miny) ? (maxx - minx) : (maxy - miny));
    int bits = 1;
    while (bits < 22 && (1u << bits) <= span) ++bits;
    std::uint64_t* ka = keys_.data();
    std::uint64_t* kb = keys_.data() + n;
    std::uint32_t* ia = order_.data();
    std::uint32_t* ib = order_.data() + n;
    for (std::size_t i = 0; i < n; ++i) {
      ka[i] = hilbert_key(static_cast<std::uint32_t>(pts_[i].x - minx),
                          static_cast<std::uint32_t>(pts_[i].y - miny), bits);
      ia[i] = static_cast<std::uint32_t>(i);
      // BRIO (biased randomised insertion order): a hashed geometric round
      // number above the Hilbert key, so most points are inserted late, into
      // an already dense mesh, where cavities are small.
      std::uint32_t h = static_cast<std::uint32_t>(i) * 2654435761u;
      h ^= h >> 15;
      h *= 2246822519u;
      h ^= h >> 13;
      const int zeros = __builtin_ctz(h | (1u << (kRounds - 1)));
      ka[i] |= static_cast<std::uint64_t>(kRounds - 1 - zeros) << (2 * bits);
    }
    // LSD radix sort, 8 bits a pass (stable, so ties keep input order).
    const int passes = (2 * bits + kRoundBits + 7) / 8;
    for (int pass = 0; pass < passes; ++pass) {
      std::size_t count[257] = {};
      const int shift = 8 * pass;
      for (std::size_t i = 0; i < n; ++i) ++count[((ka[i] >> shift) & 0xFF) + 1];
      for (int b = 0; b < 256; ++b) count[b + 1] += count[b];
      for (std::size_t i = 0; i < n; ++i) {
        const std::size_t dst = count[(ka[i] >> shift) & 0xFF]++;
        kb[dst] = ka[i];
        ib[dst] = ia[i];
      }
      std::uint64_t* tk = ka;
      ka = kb;
      kb = tk;
      std::uint32_t* ti = ia;
      ia = ib;
      ib = ti;
    }
    sorted_ = ia;
  }

  Result<DelaunayStats> run(std::span<MeshTriangle> out) {
    const std::size_t n = pts_.size();
    sort_hilbert();
    PETRA_TRY(start());
    for (std::size_t k = 3; k < n; ++k) insert(static_cast<std::int32_t>(sorted_[k]));
    return compact(out);
  }

 private:
  const IntPoint& P(std::int32_t i) const { return pts_[static_cast<std::size_t>(i)]; }
  MeshTriangle& T(std::int32_t t) { return pool_[static_cast<std::size_t>(t)]; }

  static int ghost_index(const MeshTriangle& t) {
    return t.v[0] == kGhost ? 0 : (t.v[1] == kGhost ? 1 : (t.v[2] == kGhost ? 2 : -1));
  }

  // Is p strictly inside t's circumcircle (ghosts: strictly outside the hull
  // edge, or on the open hull segment)?
  bool conflict(std::int32_t t, const IntPoint& p) {
    const MeshTriangle& tri = T(t);
    const int g = ghost_index(tri);
    if (g < 0) return incircle_sign(P(tri.v[0]), P(tri.v[1]), P(tri.v[2]), p) > 0;
    const IntPoint& u = P(tri.v[(g + 1) % 3]);
    const IntPoint& w = P(tri.v[(g + 2) % 3]);
    const std::int64_t o = orient2d(u, w, p);
    if (o != 0) return o > 0;
    const std::int64_t along_u = static_cast<std::int64_t>(p.x - u.x) * (w.x - u.x) +
                                 static_cast<std::int64_t>(p.y - u.y) * (w.y - u.y);
    const std::int64_t along_w = static_cast<std::int64_t>(p.x - w.x) * (u.x - w.x) +
                                 static_cast<std::int64_t>(p.y - w.y) * (u.y - w.y);
    return along_u > 0 && along_w > 0;
  }

  std::int32_t new_triangle() {
    if (free_head_ >= 0) {
      const std::int32_t t = free_head_;
      free_head_ = T(t).n[0];
      return t;
    }
    PETRA_ASSERT(pool_used_ < pool_.size());
    return static_cast<std::int32_t>(pool_used_++);
  }
  void free_triangle(std::int32_t t) {
    T(t).v[0] = kDead;
    T(t).n[0] = free_head_;
    free_head_ = t;
  }

  Status start() {
    const std::size_t n = pts_.size();
    const std::int32_t a = static_cast<std::int32_t>(sorted_[0]);
    std::size_t kb = 1;
    while (kb < n && P(static_cast<std::int32_t>(sorted_[kb])) == P(a)) ++kb;
    if (kb == n) return Error::make(Errc::degenerate, "delaunay: all %zu points coincide", n);
    const std::int32_t b = static_cast<std::int32_t>(sorted_[kb]);
    std::size_t kc = kb + 1;
    while (kc < n && orient2d(P(a), P(b), P(static_cast<std::int32_t>(sorted_[kc]))) == 0) ++kc;
    if (kc == n) return Error::make(Errc::degenerate, "delaunay: all %zu points are collinear", n);
    // Put b and c in slots 1 and 2; the points they displace are inserted later.
    std::uint32_t tmp = sorted_[1];
    sorted_[1] = sorted_[kb];
    sorted_[kb] = tmp;
    tmp = sorted_[2];
    sorted_[2] = sorted_[kc];
    sorted_[kc] = tmp;
    std::int32_t v0 = static_cast<std::int32_t>(sorted_[0]);
    std::int32_t v1 = static_cast<std::int32_t>(sorted_[1]);
    std::int32_t v2 = static_cast<std::int32_t>(sorted_[2]);
    if (orient2d(P(v0), P(v1), P(v2)) < 0) {
      const std::int32_t s = v1;
      v1 = v2;
      v2 = s;
    }
    const std::int32_t t0 = new_triangle();
    T(t0) = MeshTriangle{{v0, v1, v2}, {-1, -1, -1}};
    const std::int32_t verts[3] = {v0, v1, v2};
    std::int32_t ghosts[3];
    for (int i = 0; i < 3; ++i) {
      // Ghost across edge opposite v[i]: edge v[i+1] -> v[i+2] reversed.
      ghosts[i] = new_triangle();
      T(ghosts[i]) = MeshTriangle{{verts[(i + 2) % 3], verts[(i + 1) % 3], kGhost}, {-1, -1, t0}};
      T(t0).n[i] = ghosts[i];
    }
    // Ghost (w, u, G) for edge u->w: neighbours across (u, G) and (G, w).
    for (int i = 0; i < 3; ++i) {
      MeshTriangle& g = T(ghosts[i]);
      // g = (v[i+2], v[i+1], G). Edge opposite v[i+2] is v[i+1] -> G: shared with
      // the ghost whose edge is G -> v[i+1], i.e. ghosts[(i + 2) % 3].
      g.n[0] = ghosts[(i + 2) % 3];
      // Edge opposite v[i+1] is G -> v[i+2]: shared with ghosts[(i + 1) % 3].
      g.n[1] = ghosts[(i + 1) % 3];
    }
    last_ = t0;
    vertices_ = 3;
    for (std::size_t i = 0; i < mark_.size(); ++i) mark_[i] = 0;
    for (std::size_t i = 0; i < link_.size(); ++i) link_[i] = -1;
    return {};
  }

  // A triangle in conflict with p, or -1 when p duplicates a vertex.
  std::int32_t locate(const IntPoint& p) {
    std::int32_t t = last_;
    const std::size_t max_steps = pool_used_ + 16;
    for (std::size_t step = 0; step < max_steps; ++step) {
      ++walk_steps_;
      const MeshTriangle& tri = T(t);
      if (ghost_index(tri) >= 0) return t;  // entered through a hull edge p is beyond
      rng_ = rng_ * 1103515245u + 12345u;
      const int e0 = static_cast<int>((rng_ >> 16) % 3);
      bool moved = false;
      for (int k = 0; k < 3 && !moved; ++k) {
        const int i = (e0 + k) % 3;
        if (orient2d(P(tri.v[(i + 1) % 3]), P(tri.v[(i + 2) % 3]), p) < 0) {
          t = tri.n[i];
          moved = true;
        }
      }
      if (!moved) {
        for (int i = 0; i < 3; ++i)
          if (P(tri.v[i]) == p) return -1;
        return t;
      }
    }
    // Fallback: linear scan (never seen in tests; bounded by the pool size).
    ++walk_fallbacks_;
    for (std::size_t i = 0; i < pool_used_; ++i) {
      const std::int32_t c = static_cast<std::int32_t>(i);
      const MeshTriangle& tri = T(c);
      if (tri.v[0] == kDead) continue;
      for (int k = 0; k < 3; ++k)
        if (tri.v[k] != kGhost && P(tri.v[k]) == p) return -1;
    }
    for (std::size_t i = 0; i < pool_used_; ++i) {
      const std::int32_t c = static_cast<std::int32_t>(i);
      if (T(c).v[0] != kDead && conflict(c, p)) return c;
    }
    // cppcheck-suppress incorrectStringBooleanError ; the message is the assert's text
    PETRA_ASSERT(false && "delaunay: no conflicting triangle");
    return -1;
  }

  std::size_t slot(std::int32_t v) const {
    return v == kGhost ? pts_.size() : static_cast<std::size_t>(v);
  }

  void insert(std::int32_t pi) {
    const IntPoint& p = P(pi);
    const std::int32_t t0 = locate(p);
    if (t0 < 0) {
      ++duplicates_;
      return;
    }
    ++stamp_;
    const std::uint32_t in = 2 * stamp_, out = 2 * stamp_ + 1;
    std::size_t sp = 0, nc = 0, nb = 0;
    stack_[sp++] = t0;
    mark_[static_cast<std::size_t>(t0)] = in;
    cavity_[nc++] = t0;
    while (sp > 0) {
      const std::int32_t t = stack_[--sp];
      for (int i = 0; i < 3; ++i) {
        const std::int32_t nbr = T(t).n[i];
        std::uint32_t& m = mark_[static_cast<std::size_t>(nbr)];
        if (m == in) continue;
        if (m != out && conflict(nbr, p)) {
          m = in;
          stack_[sp++] = nbr;
          cavity_[nc++] = nbr;
          continue;
        }
        m = out;
        const MeshTriangle& o = T(nbr);
        const int back = o.n[0] == t ? 0 : (o.n[1] == t ? 1 : 2);
        boundary_[nb++] = Boundary{T(t).v[(i + 1) % 3], T(t).v[(i + 2) % 3], nbr, back};
      }
    }
    for (std::size_t i = 0; i < nc; ++i) free_triangle(cavity_[i]);
    // One new triangle (a, b, p) per boundary edge, then link the fan.
    std::int32_t first_real = -1;
    for (std::size_t i = 0; i < nb; ++i) {
      const Boundary& e = boundary_[i];
      const std::int32_t t = new_triangle();
      T(t) = MeshTriangle{{e.a, e.b, pi}, {-1, -1, e.outside}};
      T(e.outside).n[e.outside_at] = t;
      link_[slot(e.a)] = t;
      stack_[i] = t;  // reuse: the new triangles
      if (first_real < 0 && e.a != kGhost && e.b != kGhost) first_real = t;
    }
    for (std::size_t i = 0; i < nb; ++i) {
      const std::int32_t t = stack_[i];
      const std::int32_t u = link_[slot(T(t).v[1])];  // the triangle (b, c, p)
      T(t).n[0] = u;
      T(u).n[1] = t;
    }
    PETRA_ASSERT(first_real >= 0);
    last_ = first_real;
    ++vertices_;
  }

  Result<DelaunayStats> compact(std::span<MeshTriangle> out) {
    DelaunayStats stats;
    // Reuse the stack as the pool -> output index map.
    std::size_t count = 0;
    for (std::size_t i = 0; i < pool_used_; ++i) {
      const MeshTriangle& t = pool_[i];
      const bool real = t.v[0] != kDead && ghost_index(t) < 0;
      stack_[i] = real ? static_cast<std::int32_t>(count++) : -1;
      if (t.v[0] != kDead && !real) ++stats.hull_edges;
    }
    if (count > out.size())
      return Error::make(Errc::capacity_exceeded, "delaunay: %zu triangles, output holds %zu",
                         count, out.size());
    for (std::size_t i = 0; i < pool_used_; ++i) {
      if (stack_[i] < 0) continue;
      MeshTriangle r = pool_[i];
      for (int k = 0; k < 3; ++k) r.n[k] = stack_[static_cast<std::size_t>(r.n[k])];
      out[static_cast<std::size_t>(stack_[i])] = r;
    }
    stats.triangles = count;
    stats.vertices = vertices_;
    stats.duplicates = duplicates_;
    stats.walk_steps = walk_steps_;
    stats.walk_fallbacks = walk_fallbacks_;
    return stats;
  }

  std::span<const IntPoint> pts_;
  Arena& arena_;
  std::span<MeshTriangle> pool_;
  std::span<std::uint32_t> mark_;
  std::span<std::int32_t> stack_, cavity_, link_;
  std::span<Boundary> boundary_;
  std::span<std::uint64_t> keys_;
  std::span<std::uint32_t> order_;
  std::uint32_t* sorted_ = nullptr;
  std::size_t pool_used_ = 0;
  std::int32_t free_head_ = -1;
  std::int32_t last_ = 0;
  std::uint32_t stamp_ = 0;
  std::uint32_t rng_ = 1;
  std::size_t vertices_ = 0, duplicates_ = 0, walk_steps_ = 0, walk_fallbacks_ = 0;
};

}  // namespace

std::size_t delaunay_incremental_scratch_bytes(std::size_t n) {
  const std::size_t cap = pool_capacity(n);
  return arena_bytes_for<MeshTriangle>(cap) + 3 * arena_bytes_for<std::int32_t>(cap) +
         arena_bytes_for<Boundary>(cap) + arena_bytes_for<std::int32_t>(n + 1) +
         arena_bytes_for<std::uint64_t>(2 * n) + arena_bytes_for<std::uint32_t>(2 * n);
}

Status check_delaunay_input(std::span<const IntPoint> points) {
  const std::size_t n = points.size();
  if (n < 3) return Error::make(Errc::degenerate, "delaunay: %zu points, need at least 3", n);
  if (n > 0x3FFFFFFF) return Error::make(Errc::capacity_exceeded, "delaunay: %zu points", n);
  for (std::size_t i = 0; i < n; ++i) {
    const IntPoint& p = points[i];
    if (p.x > kPredicateMaxAbsCoord || p.x < -kPredicateMaxAbsCoord ||
        p.y > kPredicateMaxAbsCoord || p.y < -kPredicateMaxAbsCoord)
      return Error::make(Errc::out_of_range, "delaunay: point %zu (%d, %d) beyond +-%d", i, p.x,
                         p.y, kPredicateMaxAbsCoord);
  }
  return {};
}

std::size_t delaunay_scratch_bytes(std::size_t n) {
  const std::size_t a = delaunay_incremental_scratch_bytes(n), b = delaunay_raster_scratch_bytes(n);
  return a > b ? a : b;
}

std::size_t delaunay_scratch_bytes(std::size_t n, std::size_t max_rows) {
  const std::size_t a = delaunay_incremental_scratch_bytes(n),
                    b = delaunay_raster_scratch_bytes(n, max_rows);
  return a > b ? a : b;
}

Result<DelaunayStats> delaunay_triangulate_incremental(std::span<const IntPoint> points,
                                                       std::span<MeshTriangle> triangles,
                                                       Arena& scratch) {
  PETRA_TRY(check_delaunay_input(points));
  ArenaScope scope(scratch);
  Builder builder(points, scratch);
  PETRA_TRY(builder.allocate());
  return builder.run(triangles);
}

Result<DelaunayStats> delaunay_triangulate(std::span<const IntPoint> points,
                                           std::span<MeshTriangle> triangles, Arena& scratch) {
  PETRA_TRY(check_delaunay_input(points));
  if (is_raster_ordered(points)) return delaunay_triangulate_raster(points, triangles, scratch);
  return delaunay_triangulate_incremental(points, triangles, scratch);
}

}  // namespace petra
