// One alpha-expansion of the graph-cut matcher: the binary problem "which
// current assignments stay active, which assignments of disparity alpha become
// active" as a graph, its minimum cut, and the update of the labelling.
//
// Node meaning (KZ 2001): an "old" node per pixel whose active disparity is
// not alpha (source side = stays active), an "alpha" node per pixel whose
// (p, alpha) is valid and not yet active (sink side = becomes active).
// Unary costs go to terminal links; Potts pairs between two old nodes of the
// same disparity or two alpha nodes become symmetric arcs of weight V; the
// uniqueness of left pixel p (old(p) vs alpha(p)) and of right pixel q (the
// old node matched to q vs the alpha node ending at q) become infinite arcs
// old -> alpha, cut exactly when both would be active.
//
// Exact reduction before the cut. A set R of alpha assignments can be fixed
// inactive when each member's own cost of becoming active (D - K, minus the
// Potts terms it would save with neighbours already at alpha) is at least the
// Potts weight towards free neighbours outside R: switching all of R off in
// any cut then never costs more. The largest such R is found by starting from
// every candidate with a non-negative cost and removing, with a worklist, the
// members whose condition fails. Likewise a set Q of old assignments without
// a free alpha competitor can be fixed active when each member's cost of
// staying (<= 0) covers its Potts weight towards free old neighbours outside
// Q. Fixed nodes leave the graph; their Potts terms become terminal weights of
// their free neighbours. The minimum, and so the energy reached, is unchanged;
// only the graph shrinks.
#include <algorithm>
#include <climits>
#include <cstdlib>

#include "algo/stereo/match_graphcut.hpp"

namespace petra {

namespace {

// alpha_node_ states besides a node id (>= 0).
constexpr std::int32_t kInvalid = -1;        // (p, alpha) outside the image or in shadow
constexpr std::int32_t kFixedActive = -2;    // p already has disparity alpha
constexpr std::int32_t kFixedInactive = -3;  // in R
constexpr std::int32_t kFree = -4;           // a node, id not yet given
// Slack of a forced-inactive alpha assignment: no neighbour sum reaches it.
constexpr std::int32_t kOutsideBand = INT32_MAX / 2;
// old_node_ states besides a node id.
constexpr std::int32_t kNoOld = -1;      // occluded or already at alpha
constexpr std::int32_t kFixedKept = -2;  // in Q

// Potts weight between p and its right / lower neighbour, from p's edge bits.
struct Potts {
  std::int32_t weight[2];  // indexed by the edge bit
  std::int32_t right(std::uint8_t bits) const { return weight[bits & 1]; }
  std::int32_t down(std::uint8_t bits) const { return weight[(bits >> 1) & 1]; }
};

constexpr std::int32_t kInf = MaxFlow<6>::kInfiniteCapacity;

// What the graph's construction reads and writes: locals of build_graph,
// whose per-pixel steps below are inlined into its loop.
struct GraphBuild {
  MaxFlow<6>& maxflow;
  Potts v;
  int w, h;
  int disp_min, d_alpha;
  std::int32_t k;
  const std::int16_t* label;
  const std::int16_t* acost;
  const std::uint8_t* ae;
  const std::uint8_t* oe;
  const std::int32_t* keep;
  const std::int16_t* owner;
  std::int32_t* an;
  std::int32_t* on;
  std::int32_t* node_pixel;
  std::int64_t base;  // the cut of "change nothing"

  void link(std::int32_t i, std::int32_t j, std::int32_t cap, std::int32_t rev) {
    const bool added = maxflow.add_edge(i, j, cap, rev);
    PETRA_ASSERT(added);  // degree <= 6 by construction
  }
};

// The alpha node of free pixel p (row starts at p - x; q is (x, alpha)'s
// strip pixel): Potts arcs to earlier free alpha nodes, Potts terms of fixed
// neighbours as terminal weights, and the uniqueness arc from the old node
// already matched to q.
[[gnu::always_inline]] inline std::int32_t add_alpha_node(GraphBuild& g, int p, int x, int y,
                                                          int row, int q) {
  const int w = g.w;
  std::int32_t* an = g.an;
  const std::uint8_t* ae = g.ae;
  const std::int32_t a_id = g.maxflow.add_node();
  g.node_pixel[a_id] = 2 * p;
  std::int32_t if_active = g.acost[p] - g.k;
  std::int32_t if_inactive = 0;
  auto pair = [&](std::int32_t st, std::int32_t v) {
    if (st >= 0) {
      g.link(a_id, st, v, v);
    } else if (st == kFixedActive) {
      if_inactive += v;
    } else if (st == kFixedInactive) {
      if_active += v;
    }
  };
  if (x > 0) pair(an[p - 1], g.v.right(ae[p - 1]));
  if (y > 0) pair(an[p - w], g.v.down(ae[p - w]));
  // Free right/lower neighbours link back when their turn comes.
  if (x + 1 < w && an[p + 1] < kInvalid) pair(an[p + 1], g.v.right(ae[p]));
  if (y + 1 < g.h && an[p + w] < kInvalid) pair(an[p + w], g.v.down(ae[p]));
  const std::int32_t net = if_active - if_inactive;
  if (net > 0) {
    g.maxflow.add_terminal_weights(a_id, net, 0);
  } else {
    g.maxflow.add_terminal_weights(a_id, 0, -net);
    g.base -= net;
  }
  an[p] = a_id;
  // The old node already matched to the same right pixel, if it came first.
  const int owner = g.owner[q];
  if (owner >= 0 && owner < x) {
    PETRA_ASSERT(g.on[row + owner] >= 0);
    g.link(g.on[row + owner], a_id, kInf, 0);
  }
  return a_id;
}

// The old node of free pixel p: uniqueness arcs to its own alpha node and
// to the earlier alpha node ending on its right pixel, Potts arcs to earlier
// free old nodes of its disparity, kept neighbours' terms as terminal weights.
[[gnu::always_inline]] inline void add_old_node(GraphBuild& g, int p, int x, int y, int row,
                                                std::int32_t a_id) {
  const int w = g.w;
  const std::int16_t* label = g.label;
  const std::uint8_t* oe = g.oe;
  const std::int32_t o_id = g.maxflow.add_node();
  g.node_pixel[o_id] = 2 * p + 1;
  const int lab = label[p];
  if (a_id >= 0) g.link(o_id, a_id, kInf, 0);
  const int xr = x - (g.disp_min + lab) + g.d_alpha;
  if (xr >= 0 && xr < x && g.an[row + xr] >= 0) g.link(o_id, g.an[row + xr], kInf, 0);
  std::int32_t if_dropped = 0;
  auto pair = [&](int n, std::int32_t v, bool earlier) {
    if (label[n] != lab) return;
    const std::int32_t st = g.on[n];
    if (st == kFixedKept) {
      if_dropped += v;
    } else if (earlier) {
      g.link(o_id, st, v, v);
    }
  };
  if (x > 0) pair(p - 1, g.v.right(oe[p - 1]), true);
  if (y > 0) pair(p - w, g.v.down(oe[p - w]), true);
  if (x + 1 < w) pair(p + 1, g.v.right(oe[p]), false);
  if (y + 1 < g.h) pair(p + w, g.v.down(oe[p]), false);
  const std::int32_t net = g.keep[p] - if_dropped;
  if (net > 0) {
    g.maxflow.add_terminal_weights(o_id, 0, net);
    g.base += net;
  } else {
    g.maxflow.add_terminal_weights(o_id, -net, 0);
  }
  g.on[p] = o_id;
}

}  // namespace

// The constants of one expansion on alpha, shared by its steps.
struct GraphCutMatcher::Expansion {
  int alpha = 0;
  int d_alpha = 0;  // alpha's disparity
  int shift = 0;    // strip column of (x, alpha) is x + shift
  int x_lo = 0;     // (x, alpha) lands in the image for x in [x_lo, x_hi)
  int x_hi = 0;
};

std::int64_t GraphCutMatcher::expand(int alpha, std::int64_t& nodes_used, int band) {
  Expansion e;
  e.alpha = alpha;
  e.d_alpha = disp_min_ + alpha;
  e.shift = roi_x_ - e.d_alpha - strip_x0_;
  e.x_lo = std::clamp(e.d_alpha - roi_x_, 0, w_);
  e.x_hi = std::clamp(image_w_ + e.d_alpha - roi_x_, e.x_lo, w_);

  alpha_assignments(e, band);
  if (prune_) fix_inactive_alphas();
  old_assignments(e);
  if (prune_) fix_kept_olds();
  const std::int64_t base = build_graph(e);
  const std::int32_t num_nodes = maxflow_.num_nodes();
  nodes_used += num_nodes;
  if (num_nodes == 0) return 0;

  const std::int64_t delta = maxflow_.solve() - base;
  if (delta >= 0) return 0;  // ties keep the current labelling
  refresh_changed(apply_cut(e, num_nodes));
  return delta;
}

// A: alpha assignments: fixed active, invalid, or candidate (cost, edge bits).
void GraphCutMatcher::alpha_assignments(const Expansion& e, int band) {
  const int w = w_;
  const int h = h_;
  const int sw = strip_w_;
  const int alpha = e.alpha;
  const int shift = e.shift;
  const int x_lo = e.x_lo;
  const int x_hi = e.x_hi;
  const std::uint8_t* lf = left_flags_.data();
  const std::uint8_t* rf = right_flags_.data();
  const std::int16_t* label = label_.data();
  std::int16_t* acost = alpha_cost_.data();
  std::uint8_t* ae = alpha_edges_.data();
  std::int32_t* an = alpha_node_.data();
  std::int32_t* aslack = alpha_slack_.data();
  for (int y = 0; y < h; ++y) {
    const int row = y * w;
    const int qrow = y * sw + shift;
    for (int x = 0; x < w; ++x) {
      const int p = row + x;
      if (x < x_lo || x >= x_hi) {
        an[p] = kInvalid;
        continue;
      }
      const std::uint8_t f = lf[p] | rf[qrow + x];
      ae[p] = static_cast<std::uint8_t>(f & 3);
      if (label[p] == alpha) {
        an[p] = kFixedActive;
      } else if ((f & kUnusable) != 0) {
        an[p] = kInvalid;
      } else if (band >= 0 && guide_[p] >= 0 && std::abs(guide_[p] - alpha) > band) {
        // Outside the guided band: inactive whatever its neighbours do.
        an[p] = kFixedInactive;
        aslack[p] = kOutsideBand;
      } else {
        an[p] = kFree;
        acost[p] = static_cast<std::int16_t>(gc::bt_cost(left_[p], right_[qrow + x], clip2_));
      }
    }
  }
}

// R: the alpha assignments fixed inactive (the header's reduction).
void GraphCutMatcher::fix_inactive_alphas() {
  const int w = w_;
  const int h = h_;
  const std::int32_t k = k_;
  const Potts v{{lambda1_, lambda2_}};
  const std::int16_t* acost = alpha_cost_.data();
  const std::uint8_t* ae = alpha_edges_.data();
  std::int32_t* an = alpha_node_.data();
  std::int32_t* aslack = alpha_slack_.data();
  std::int32_t* work = worklist_.data();
  int top = 0;
  // R starts as every candidate whose activation costs >= 0 on its own.
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const int p = y * w + x;
      if (an[p] != kFree) continue;
      std::int32_t s = acost[p] - k;
      if (x > 0 && an[p - 1] == kFixedActive) s -= v.right(ae[p - 1]);
      if (x + 1 < w && an[p + 1] == kFixedActive) s -= v.right(ae[p]);
      if (y > 0 && an[p - w] == kFixedActive) s -= v.down(ae[p - w]);
      if (y + 1 < h && an[p + w] == kFixedActive) s -= v.down(ae[p]);
      if (s >= 0) {
        an[p] = kFixedInactive;
        aslack[p] = s;
      }
    }
  }
  // Members must cover their weight towards free neighbours; removing one
  // may break its neighbours' condition in turn.
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const int p = y * w + x;
      if (an[p] != kFixedInactive) continue;
      std::int32_t s = aslack[p];
      if (x > 0 && an[p - 1] == kFree) s -= v.right(ae[p - 1]);
      if (x + 1 < w && an[p + 1] == kFree) s -= v.right(ae[p]);
      if (y > 0 && an[p - w] == kFree) s -= v.down(ae[p - w]);
      if (y + 1 < h && an[p + w] == kFree) s -= v.down(ae[p]);
      aslack[p] = s;
      if (s < 0) work[top++] = p;
    }
  }
  auto drop = [&](int n, std::int32_t wt) {
    if (an[n] != kFixedInactive) return;
    const std::int32_t before = aslack[n];
    aslack[n] = before - wt;
    if (before >= 0 && aslack[n] < 0) work[top++] = n;
  };
  while (top > 0) {
    const int p = work[--top];
    an[p] = kFree;
    const int y = p / w;
    const int x = p - y * w;
    if (x > 0) drop(p - 1, v.right(ae[p - 1]));
    if (x + 1 < w) drop(p + 1, v.right(ae[p]));
    if (y > 0) drop(p - w, v.down(ae[p - w]));
    if (y + 1 < h) drop(p + w, v.down(ae[p]));
  }
}

// B: old assignments. Q candidates have no free alpha competitor (left or
// right) and a cost of staying <= 0.
void GraphCutMatcher::old_assignments(const Expansion& e) {
  const int w = w_;
  const int h = h_;
  const int alpha = e.alpha;
  const int d_alpha = e.d_alpha;
  const std::int16_t* label = label_.data();
  const std::int32_t* keep = keep_.data();
  const std::int32_t* an = alpha_node_.data();
  std::int32_t* on = old_node_.data();
  std::int32_t* oslack = old_slack_.data();
  for (int y = 0; y < h; ++y) {
    const int row = y * w;
    for (int x = 0; x < w; ++x) {
      const int p = row + x;
      const int lab = label[p];
      if (lab < 0 || lab == alpha) {
        on[p] = kNoOld;
        continue;
      }
      const int xr = x - (disp_min_ + lab) + d_alpha;  // alpha pixel ending on the same right pixel
      const bool competed = an[p] == kFree || (xr >= 0 && xr < w && an[row + xr] == kFree);
      if (prune_ && !competed && keep[p] <= 0) {
        on[p] = kFixedKept;
        oslack[p] = -keep[p];
      } else {
        on[p] = kFree;
      }
    }
  }
}

// Q: the old assignments fixed kept, reduced as R is.
void GraphCutMatcher::fix_kept_olds() {
  const int w = w_;
  const int h = h_;
  const Potts v{{lambda1_, lambda2_}};
  const std::int16_t* label = label_.data();
  const std::uint8_t* oe = old_edges_.data();
  std::int32_t* on = old_node_.data();
  std::int32_t* oslack = old_slack_.data();
  std::int32_t* work = worklist_.data();
  int top = 0;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const int p = y * w + x;
      if (on[p] != kFixedKept) continue;
      const int lab = label[p];
      std::int32_t s = oslack[p];
      if (x > 0 && label[p - 1] == lab && on[p - 1] == kFree) s -= v.right(oe[p - 1]);
      if (x + 1 < w && label[p + 1] == lab && on[p + 1] == kFree) s -= v.right(oe[p]);
      if (y > 0 && label[p - w] == lab && on[p - w] == kFree) s -= v.down(oe[p - w]);
      if (y + 1 < h && label[p + w] == lab && on[p + w] == kFree) s -= v.down(oe[p]);
      oslack[p] = s;
      if (s < 0) work[top++] = p;
    }
  }
  auto drop = [&](int n, int lab, std::int32_t wt) {
    if (label[n] != lab || on[n] != kFixedKept) return;
    const std::int32_t before = oslack[n];
    oslack[n] = before - wt;
    if (before >= 0 && oslack[n] < 0) work[top++] = n;
  };
  while (top > 0) {
    const int p = work[--top];
    on[p] = kFree;
    const int y = p / w;
    const int x = p - y * w;
    const int lab = label[p];
    if (x > 0) drop(p - 1, lab, v.right(oe[p - 1]));
    if (x + 1 < w) drop(p + 1, lab, v.right(oe[p]));
    if (y > 0) drop(p - w, lab, v.down(oe[p - w]));
    if (y + 1 < h) drop(p + w, lab, v.down(oe[p]));
  }
}

// C: the graph, built in scan order. Ids are given as nodes appear, so
// each arc is added from the later of its two ends. Returns `base`, the cut
// of "change nothing" (every node on the source side), so the energy change
// is flow - base.
std::int64_t GraphCutMatcher::build_graph(const Expansion& e) {
  const Status cleared = maxflow_.reset(0);
  PETRA_ASSERT(cleared.ok());
  const int w = w_;
  const int h = h_;
  const int sw = strip_w_;
  const int shift = e.shift;
  GraphBuild g{.maxflow = maxflow_,
               .v = {{lambda1_, lambda2_}},
               .w = w,
               .h = h,
               .disp_min = disp_min_,
               .d_alpha = e.d_alpha,
               .k = k_,
               .label = label_.data(),
               .acost = alpha_cost_.data(),
               .ae = alpha_edges_.data(),
               .oe = old_edges_.data(),
               .keep = keep_.data(),
               .owner = owner_.data(),
               .an = alpha_node_.data(),
               .on = old_node_.data(),
               .node_pixel = node_pixel_.data(),
               .base = 0};
  for (int y = 0; y < h; ++y) {
    const int row = y * w;
    const int qrow = y * sw + shift;
    for (int x = 0; x < w; ++x) {
      const int p = row + x;
      std::int32_t a_id = -1;
      if (g.an[p] == kFree) a_id = add_alpha_node(g, p, x, y, row, qrow + x);
      if (g.on[p] == kFree) add_old_node(g, p, x, y, row, a_id);
    }
  }
  return g.base;
}

// Release the matches that end, then take the new ones (a right pixel
// freed and retaken in the same move is released first). One pass over the
// nodes: the alpha nodes taken are compacted to the front of node_pixel
// (their index never passes the node id being read). Returns how many
// pixels changed (listed in the worklist).
int GraphCutMatcher::apply_cut(const Expansion& e, std::int32_t num_nodes) {
  const int w = w_;
  const int sw = strip_w_;
  const int alpha = e.alpha;
  const int shift = e.shift;
  std::int16_t* label = label_.data();
  const std::int16_t* acost = alpha_cost_.data();
  const std::int32_t* on = old_node_.data();
  std::int32_t* node_pixel = node_pixel_.data();
  std::int32_t* work = worklist_.data();
  int changed = 0;
  int taken = 0;
  for (std::int32_t id = 0; id < num_nodes; ++id) {
    if (!maxflow_.in_sink_side(id)) continue;
    const std::int32_t np = node_pixel[id];
    if ((np & 1) == 0) {
      node_pixel[taken++] = np;
      continue;
    }
    const int p = np >> 1;
    const int y = p / w;
    const int x = p - y * w;
    owner_[y * sw + roi_x_ + x - (disp_min_ + label[p]) - strip_x0_] = -1;
    label[p] = kOccluded;
    work[changed++] = p;
  }
  for (int t = 0; t < taken; ++t) {
    const int p = node_pixel[t] >> 1;
    const int y = p / w;
    const int x = p - y * w;
    const int q = y * sw + shift + x;
    PETRA_ASSERT(owner_[q] < 0);
    owner_[q] = static_cast<std::int16_t>(x);
    if (on[p] < 0) work[changed++] = p;  // (pixels that lost an old node are listed)
    label[p] = static_cast<std::int16_t>(alpha);
    cost_[p] = acost[p];
  }
  return changed;
}

// The cached terms of the changed pixels and of their neighbours.
void GraphCutMatcher::refresh_changed(int changed) {
  const int w = w_;
  const int h = h_;
  const std::int32_t* work = worklist_.data();
  for (int c = 0; c < changed; ++c) {
    const int p = work[c];
    const int y = p / w;
    const int x = p - y * w;
    refresh_pixel(p, x, y);
    if (x > 0) refresh_pixel(p - 1, x - 1, y);
    if (x + 1 < w) refresh_pixel(p + 1, x + 1, y);
    if (y > 0) refresh_pixel(p - w, x, y - 1);
    if (y + 1 < h) refresh_pixel(p + w, x, y + 1);
  }
}

}  // namespace petra
