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
#include <algorithm>

#include "algo/match_graphcut.hpp"

namespace petra {

namespace {

// States of (p, alpha) in alpha_node_ besides a node id (>= 0).
constexpr std::int32_t kInvalid = -1;      // outside the image or in shadow: no term
constexpr std::int32_t kFixedActive = -2;  // p already has disparity alpha
constexpr std::int32_t kPruned = -3;       // fixed inactive by the exact reduction
constexpr std::int32_t kNoNode = -1;

}  // namespace

std::int64_t GraphCutMatcher::expand(int alpha, std::int64_t& nodes_used) {
  const int w = w_;
  const int h = h_;
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
  // Potts weight of the pair (p, right or lower neighbour) whose matches start at q.
  auto v_right = [&](int p, int q) { return ((lf[p] | rf[q]) & kEdgeRight) != 0 ? l2 : l1; };
  auto v_down = [&](int p, int q) { return ((lf[p] | rf[q]) & kEdgeDown) != 0 ? l2 : l1; };
  auto usable = [&](int p, int q) { return ((lf[p] | rf[q]) & kUnusable) == 0; };

  // Pass 1: which nodes exist; node ids interleaved in scan order for locality.
  // An alpha node is pruned (fixed inactive) when its own cost of becoming
  // active outweighs everything its free neighbours could pay it to do so:
  // then some minimum cut leaves it inactive, so fixing it keeps the minimum.
  std::int32_t next = 0;
  for (int y = 0; y < h; ++y) {
    const int row = y * w;
    const int qrow = y * sw + shift;
    for (int x = 0; x < w; ++x) {
      const int p = row + x;
      const int lab = label[p];
      std::int32_t an = kInvalid;
      if (lab == alpha) {
        an = kFixedActive;
      } else if (x >= x_lo && x < x_hi && usable(p, qrow + x)) {
        const int q = qrow + x;
        const std::int32_t d = gc::bt_cost(left_[p], right_[q], clip2_);
        alpha_cost_[p] = static_cast<std::int16_t>(d);
        bool keep = true;
        if (prune_) {
          std::int32_t fixed_active = 0;
          std::int32_t fixed_inactive = 0;
          std::int32_t free = 0;
          auto classify = [&](std::int32_t st, std::int32_t v) {
            if (st >= 0) {
              free += v;
            } else if (st == kFixedActive) {
              fixed_active += v;
            } else {
              fixed_inactive += v;
            }
          };
          if (x > 0 && alpha_node[p - 1] != kInvalid) classify(alpha_node[p - 1], v_right(p - 1, q - 1));
          if (y > 0 && alpha_node[p - w] != kInvalid) classify(alpha_node[p - w], v_down(p - w, q - sw));
          if (x + 1 < x_hi && usable(p + 1, q + 1)) {
            const std::int32_t v = v_right(p, q);
            (label[p + 1] == alpha ? fixed_active : free) += v;
          }
          if (y + 1 < h && usable(p + w, q + sw)) {
            const std::int32_t v = v_down(p, q);
            (label[p + w] == alpha ? fixed_active : free) += v;
          }
          keep = d - k + fixed_inactive - fixed_active < free;
        }
        an = keep ? next++ : kPruned;
      }
      alpha_node[p] = an;
      old_node[p] = (lab >= 0 && lab != alpha) ? next++ : kNoNode;
    }
  }

  // Pass 2: terminal links and arcs. `base` is the cut of "change nothing"
  // (every node on the source side), so the energy change is flow - base.
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
        // Pairs with the left/upper neighbour: arcs were added from that side.
        if (x > 0) {
          const std::int32_t st = alpha_node[p - 1];
          if (st == kFixedActive) if_inactive += v_right(p - 1, q - 1);
          if (st == kPruned) if_active += v_right(p - 1, q - 1);
        }
        if (y > 0) {
          const std::int32_t st = alpha_node[p - w];
          if (st == kFixedActive) if_inactive += v_down(p - w, q - sw);
          if (st == kPruned) if_active += v_down(p - w, q - sw);
        }
        if (x + 1 < w) {
          const std::int32_t st = alpha_node[p + 1];
          if (st >= 0) {
            const std::int32_t v = v_right(p, q);
            link(an, st, v, v);
          } else if (st == kFixedActive) {
            if_inactive += v_right(p, q);
          } else if (st == kPruned) {
            if_active += v_right(p, q);
          }
        }
        if (y + 1 < h) {
          const std::int32_t st = alpha_node[p + w];
          if (st >= 0) {
            const std::int32_t v = v_down(p, q);
            link(an, st, v, v);
          } else if (st == kFixedActive) {
            if_inactive += v_down(p, q);
          } else if (st == kPruned) {
            if_active += v_down(p, q);
          }
        }
        const std::int32_t net = if_active - if_inactive;
        if (net > 0) {
          maxflow_.add_terminal_weights(an, net, 0);
        } else {
          maxflow_.add_terminal_weights(an, 0, -net);
          base -= net;
        }
        if (on >= 0) link(on, an, MaxFlow::kInfiniteCapacity, 0);
        const int owner = owner_[q];
        if (owner >= 0 && old_node[row + owner] >= 0) {
          link(old_node[row + owner], an, MaxFlow::kInfiniteCapacity, 0);
        }
      }
      if (on >= 0) {
        const int lab = label[p];
        const int q_image = roi_x_ + x - (disp_min_ + lab);
        const int qd = y * sw + q_image - strip_x0_;
        std::int32_t if_kept = cost_[p] - k;
        if (x > 0 && label[p - 1] != lab && q_image > 0 && usable(p - 1, qd - 1)) {
          if_kept += v_right(p - 1, qd - 1);
        }
        if (y > 0 && label[p - w] != lab && usable(p - w, qd - sw)) {
          if_kept += v_down(p - w, qd - sw);
        }
        if (x + 1 < w) {
          if (label[p + 1] == lab) {
            const std::int32_t v = v_right(p, qd);
            link(on, old_node[p + 1], v, v);
          } else if (q_image + 1 < image_w_ && usable(p + 1, qd + 1)) {
            if_kept += v_right(p, qd);
          }
        }
        if (y + 1 < h) {
          if (label[p + w] == lab) {
            const std::int32_t v = v_down(p, qd);
            link(on, old_node[p + w], v, v);
          } else if (usable(p + w, qd + sw)) {
            if_kept += v_down(p, qd);
          }
        }
        if (if_kept > 0) {
          maxflow_.add_terminal_weights(on, 0, if_kept);
          base += if_kept;
        } else {
          maxflow_.add_terminal_weights(on, -if_kept, 0);
        }
      }
    }
  }
  nodes_used += next;

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
        owner_[y * sw + roi_x_ + x - (disp_min_ + label[p]) - strip_x0_] = -1;
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
