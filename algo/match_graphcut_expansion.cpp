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
// only the graph shrinks (in textured scenes most assignments are clearly bad).
#include <algorithm>

#include "algo/match_graphcut.hpp"

namespace petra {

namespace {

// alpha_node_ states besides a node id (>= 0).
constexpr std::int32_t kInvalid = -1;        // (p, alpha) outside the image or in shadow
constexpr std::int32_t kFixedActive = -2;    // p already has disparity alpha
constexpr std::int32_t kFixedInactive = -3;  // in R
constexpr std::int32_t kFree = -4;           // a node, id not yet given
// old_node_ states besides a node id.
constexpr std::int32_t kNoOld = -1;     // occluded or already at alpha
constexpr std::int32_t kFixedKept = -2;  // in Q

}  // namespace

std::int64_t GraphCutMatcher::expand(int alpha, std::int64_t& nodes_used) {
  const int w = w_;
  const int h = h_;
  const int n_pixels = w * h;
  const int sw = strip_w_;
  const int d_alpha = disp_min_ + alpha;
  const int shift = roi_x_ - d_alpha - strip_x0_;  // strip column of (x, alpha) is x + shift
  const int x_lo = std::clamp(d_alpha - roi_x_, 0, w);  // (x, alpha) lands in the image
  const int x_hi = std::clamp(image_w_ + d_alpha - roi_x_, x_lo, w);
  const std::int32_t k = k_;
  const std::int32_t l1 = lambda1_;
  const std::int32_t l2 = lambda2_;
  const std::uint8_t* lf = left_flags_.data();
  const std::uint8_t* rf = right_flags_.data();
  std::int16_t* label = label_.data();
  std::int32_t* alpha_node = alpha_node_.data();
  std::int32_t* old_node = old_node_.data();
  std::int32_t* alpha_slack = alpha_slack_.data();
  std::int32_t* old_slack = old_slack_.data();
  std::int32_t* old_keep = old_keep_.data();
  std::int32_t* work = worklist_.data();

  // Potts weight of the pair (p, right or lower neighbour) whose matches start at q.
  auto v_right = [&](int p, int q) { return ((lf[p] | rf[q]) & kEdgeRight) != 0 ? l2 : l1; };
  auto v_down = [&](int p, int q) { return ((lf[p] | rf[q]) & kEdgeDown) != 0 ? l2 : l1; };
  auto usable = [&](int p, int q) { return ((lf[p] | rf[q]) & kUnusable) == 0; };
  // Neighbours n of alpha assignment (p, alpha) (q = its strip index): fn(n, V, forward).
  auto alpha_neighbours = [&](int p, int x, int y, int q, auto&& fn) {
    if (x > 0 && alpha_node[p - 1] != kInvalid) fn(p - 1, v_right(p - 1, q - 1), false);
    if (y > 0 && alpha_node[p - w] != kInvalid) fn(p - w, v_down(p - w, q - sw), false);
    if (x + 1 < w && alpha_node[p + 1] != kInvalid) fn(p + 1, v_right(p, q), true);
    if (y + 1 < h && alpha_node[p + w] != kInvalid) fn(p + w, v_down(p, q), true);
  };
  // Valid neighbours of assignment (p, l) whose match is image column qx, strip index q.
  auto old_neighbours = [&](int p, int x, int y, int q, int qx, auto&& fn) {
    if (x > 0 && qx > 0 && usable(p - 1, q - 1)) fn(p - 1, v_right(p - 1, q - 1), false);
    if (y > 0 && usable(p - w, q - sw)) fn(p - w, v_down(p - w, q - sw), false);
    if (x + 1 < w && qx + 1 < image_w_ && usable(p + 1, q + 1)) fn(p + 1, v_right(p, q), true);
    if (y + 1 < h && usable(p + w, q + sw)) fn(p + w, v_down(p, q), true);
  };
  auto match_column = [&](int x, int lab) { return roi_x_ + x - (disp_min_ + lab); };

  // A1: alpha assignments: fixed active, invalid, or candidate (with its cost).
  for (int y = 0; y < h; ++y) {
    const int row = y * w;
    const int qrow = y * sw + shift;
    for (int x = 0; x < w; ++x) {
      const int p = row + x;
      if (label[p] == alpha) {
        alpha_node[p] = kFixedActive;
      } else if (x >= x_lo && x < x_hi && usable(p, qrow + x)) {
        alpha_node[p] = kFree;
        alpha_cost_[p] = static_cast<std::int16_t>(gc::bt_cost(left_[p], right_[qrow + x], clip2_));
      } else {
        alpha_node[p] = kInvalid;
      }
    }
  }
  // A2: R starts as every candidate whose activation costs >= 0 on its own.
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const int p = y * w + x;
      if (alpha_node[p] != kFree) continue;
      std::int32_t s = alpha_cost_[p] - k;
      alpha_neighbours(p, x, y, y * sw + shift + x, [&](int n, std::int32_t v, bool) {
        if (alpha_node[n] == kFixedActive) s -= v;
      });
      if (prune_ && s >= 0) {
        alpha_node[p] = kFixedInactive;
        alpha_slack[p] = s;
      }
    }
  }
  // A3, A4: members must cover their weight towards free neighbours; remove
  // those that do not, which may in turn break their neighbours' condition.
  int top = 0;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const int p = y * w + x;
      if (alpha_node[p] != kFixedInactive) continue;
      alpha_neighbours(p, x, y, y * sw + shift + x, [&](int n, std::int32_t v, bool) {
        if (alpha_node[n] == kFree) alpha_slack[p] -= v;
      });
      if (alpha_slack[p] < 0) work[top++] = p;
    }
  }
  while (top > 0) {
    const int p = work[--top];
    alpha_node[p] = kFree;
    const int x = p % w;
    const int y = p / w;
    alpha_neighbours(p, x, y, y * sw + shift + x, [&](int n, std::int32_t v, bool) {
      if (alpha_node[n] != kFixedInactive) return;
      const std::int32_t before = alpha_slack[n];
      alpha_slack[n] = before - v;
      if (before >= 0 && alpha_slack[n] < 0) work[top++] = n;
    });
  }

  // B1: old assignments: cost of staying active (with the Potts terms towards
  // neighbours that cannot take this disparity); Q candidates have no free
  // alpha competitor on either side and a cost <= 0.
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const int p = y * w + x;
      const int lab = label[p];
      if (lab < 0 || lab == alpha) {
        old_node[p] = kNoOld;
        continue;
      }
      const int qx = match_column(x, lab);
      const int q = y * sw + qx - strip_x0_;
      std::int32_t keep = cost_[p] - k;
      old_neighbours(p, x, y, q, qx, [&](int n, std::int32_t v, bool) {
        if (label[n] != lab) keep += v;
      });
      old_keep[p] = keep;
      bool competed = alpha_node[p] == kFree;
      const int xr = qx + d_alpha - roi_x_;  // the alpha assignment ending at the same right pixel
      if (xr >= 0 && xr < w && alpha_node[y * w + xr] == kFree) competed = true;
      if (prune_ && !competed && keep <= 0) {
        old_node[p] = kFixedKept;
        old_slack[p] = -keep;
      } else {
        old_node[p] = kFree;
      }
    }
  }
  // B2, B3: as for R, with free old neighbours of the same disparity.
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const int p = y * w + x;
      if (old_node[p] != kFixedKept) continue;
      const int lab = label[p];
      const int qx = match_column(x, lab);
      old_neighbours(p, x, y, y * sw + qx - strip_x0_, qx, [&](int n, std::int32_t v, bool) {
        if (label[n] == lab && old_node[n] == kFree) old_slack[p] -= v;
      });
      if (old_slack[p] < 0) work[top++] = p;
    }
  }
  while (top > 0) {
    const int p = work[--top];
    old_node[p] = kFree;
    const int x = p % w;
    const int y = p / w;
    const int lab = label[p];
    const int qx = match_column(x, lab);
    old_neighbours(p, x, y, y * sw + qx - strip_x0_, qx, [&](int n, std::int32_t v, bool) {
      if (label[n] != lab || old_node[n] != kFixedKept) return;
      const std::int32_t before = old_slack[n];
      old_slack[n] = before - v;
      if (before >= 0 && old_slack[n] < 0) work[top++] = n;
    });
  }

  // C: node ids for what is left, interleaved in scan order for locality.
  std::int32_t next = 0;
  for (int p = 0; p < n_pixels; ++p) {
    if (alpha_node[p] == kFree) alpha_node[p] = next++;
    if (old_node[p] == kFree) old_node[p] = next++;
  }
  nodes_used += next;
  if (next == 0) return 0;

  // D: terminal links and arcs. `base` is the cut of "change nothing" (every
  // node on the source side), so the energy change is flow - base.
  const Status reset = maxflow_.reset(next);
  PETRA_ASSERT(reset.ok());
  auto link = [&](std::int32_t i, std::int32_t j, std::int32_t cap, std::int32_t rev) {
    const bool added = maxflow_.add_edge(i, j, cap, rev);
    PETRA_ASSERT(added);  // degree <= 6 by construction
  };
  std::int64_t base = 0;
  for (int y = 0; y < h; ++y) {
    const int row = y * w;
    const int qrow = y * sw + shift;
    for (int x = 0; x < w; ++x) {
      const int p = row + x;
      const std::int32_t an = alpha_node[p];
      const std::int32_t on = old_node[p];
      if (an >= 0) {
        const int q = qrow + x;
        std::int32_t if_active = alpha_cost_[p] - k;
        std::int32_t if_inactive = 0;
        alpha_neighbours(p, x, y, q, [&](int n, std::int32_t v, bool forward) {
          const std::int32_t st = alpha_node[n];
          if (st >= 0) {
            if (forward) link(an, st, v, v);
          } else if (st == kFixedActive) {
            if_inactive += v;
          } else if (st == kFixedInactive) {
            if_active += v;
          }
        });
        const std::int32_t net = if_active - if_inactive;
        if (net > 0) {
          maxflow_.add_terminal_weights(an, net, 0);
        } else {
          maxflow_.add_terminal_weights(an, 0, -net);
          base -= net;
        }
        // Uniqueness on both sides: the competing old nodes are never fixed,
        // since a free alpha node disqualifies them from Q.
        if (label[p] >= 0) {
          PETRA_ASSERT(on >= 0);
          link(on, an, MaxFlow<6>::kInfiniteCapacity, 0);
        }
        const int owner = owner_[q];
        if (owner >= 0) {
          PETRA_ASSERT(old_node[row + owner] >= 0);
          link(old_node[row + owner], an, MaxFlow<6>::kInfiniteCapacity, 0);
        }
      }
      if (on >= 0) {
        const int lab = label[p];
        const int qx = match_column(x, lab);
        std::int32_t if_dropped = 0;
        old_neighbours(p, x, y, y * sw + qx - strip_x0_, qx, [&](int n, std::int32_t v, bool forward) {
          if (label[n] != lab) return;
          const std::int32_t st = old_node[n];
          if (st >= 0) {
            if (forward) link(on, st, v, v);
          } else {
            if_dropped += v;  // a neighbour fixed in Q
          }
        });
        const std::int32_t net = old_keep[p] - if_dropped;
        if (net > 0) {
          maxflow_.add_terminal_weights(on, 0, net);
          base += net;
        } else {
          maxflow_.add_terminal_weights(on, -net, 0);
        }
      }
    }
  }

  const std::int64_t delta = maxflow_.solve() - base;
  if (delta >= 0) return 0;  // ties keep the current labelling

  // Release the matches that end, then take the new ones, row by row (a
  // right pixel is only ever contended within its row).
  for (int y = 0; y < h; ++y) {
    const int row = y * w;
    const int qrow = y * sw + shift;
    for (int x = 0; x < w; ++x) {
      const int p = row + x;
      if (old_node[p] >= 0 && maxflow_.in_sink_side(old_node[p])) {
        owner_[y * sw + match_column(x, label[p]) - strip_x0_] = -1;
        label[p] = kOccluded;
      }
    }
    for (int x = 0; x < w; ++x) {
      const int p = row + x;
      if (alpha_node[p] >= 0 && maxflow_.in_sink_side(alpha_node[p])) {
        PETRA_ASSERT(owner_[qrow + x] < 0);
        owner_[qrow + x] = static_cast<std::int16_t>(x);
        label[p] = static_cast<std::int16_t>(alpha);
        cost_[p] = alpha_cost_[p];
      }
    }
  }
  return delta;
}

}  // namespace petra
