// Max-flow / min-cut on a directed graph with source and sink terminals, by the
// Boykov-Kolmogorov method: two search trees (one grown from each terminal)
// are kept between augmentations and repaired after each one instead of being
// rebuilt, which suits the short-path, grid-like graphs of vision problems.
//
// Inputs:  nodes 0..n-1, terminal capacities per node, edges (i, j, cap, rev_cap),
//          integer capacities >= 0 (use kInfiniteCapacity for hard constraints).
// Outputs: the maximum flow value (= minimum cut cost) and, per node, its side
//          of a minimum cut (source side unless it can still reach the sink).
// Memory:  storage comes from an Arena at init, sized by the maximum node count
//          and the maximum number of edge ends per node (max_degree <= 16):
//          bytes_needed() = max_nodes * (24 + 4 + 8 * max_degree) + alignment.
//          reset()/add_*()/solve() never allocate, so one solver serves every
//          graph of a run (e.g. each alpha-expansion of the graph-cut matcher).
// Edges are stored in per-node slots (no linked lists): node i owns arcs
// [i*max_degree, i*max_degree + degree(i)), so a node's arcs share cache lines.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "algo/core/arena.hpp"
#include "algo/core/result.hpp"

namespace petra {

class MaxFlow {
 public:
  using Capacity = std::int32_t;
  using Flow = std::int64_t;

  // Large enough that no finite cut reaches it in the graphs we build, small
  // enough that residual updates never overflow int32.
  static constexpr Capacity kInfiniteCapacity = 1 << 29;
  static constexpr int kMaxDegreeLimit = 16;

  static std::size_t bytes_needed(std::int32_t max_nodes, int max_degree);

  // Takes its storage from `arena` (errors: non-positive sizes, degree above
  // kMaxDegreeLimit, arena too small).
  Status init(Arena& arena, std::int32_t max_nodes, int max_degree);

  // Starts a new graph of `num_nodes` isolated nodes with zero capacities.
  Status reset(std::int32_t num_nodes);

  // Adds capacity source->node and node->sink (both >= 0). Opposite terminal
  // capacities cancel at once (their common part is flow already sent).
  void add_terminal_weights(std::int32_t node, Capacity source_cap, Capacity sink_cap);

  // Adds arc i->j with capacity `cap` and arc j->i with `rev_cap` (i != j).
  // Each call uses one edge slot of i and one of j: returns false, and changes
  // nothing, when either node already has max_degree slots in use.
  [[nodiscard]] bool add_edge(std::int32_t i, std::int32_t j, Capacity cap, Capacity rev_cap);

  // Computes the maximum flow of the current graph (call once per reset).
  Flow solve();

  // After solve(): true when the node is on the sink side of the minimum cut.
  bool in_sink_side(std::int32_t node) const {
    const Node& n = nodes_[node];
    return n.parent != kFree && n.is_sink != 0;
  }

  std::int32_t num_nodes() const { return num_nodes_; }
  std::int32_t max_nodes() const { return max_nodes_; }
  int max_degree() const { return max_degree_; }
  int degree(std::int32_t node) const { return nodes_[node].degree; }
  // Augmenting paths found by the last solve() (a measure of its work).
  std::int64_t augmentations() const { return augmentations_; }

 private:
  // Parent codes (arc indices are >= 0).
  static constexpr std::int32_t kFree = -1;      // in no tree
  static constexpr std::int32_t kTerminal = -2;  // child of its terminal
  static constexpr std::int32_t kOrphan = -3;    // lost its parent, pending adoption
  static constexpr std::int32_t kNotActive = -1;
  static constexpr std::int32_t kNoDist = 1 << 30;

  struct Node {
    std::int32_t parent;  // arc from this node to its parent in its tree, or a code
    std::int32_t next;    // next active node; itself when last; kNotActive
    std::int32_t stamp;   // time its distance to the terminal was last verified
    std::int32_t dist;    // distance to the terminal along tree arcs
    Capacity tr_cap;      // > 0: residual source->node, < 0: residual node->sink
    std::uint8_t is_sink;
    std::uint8_t degree;
    std::uint16_t unused;
  };
  // head_slot = (head << 4) | slot of the sister arc among head's arcs.
  struct Arc {
    std::uint32_t head_slot;
    Capacity r_cap;
  };

  std::int32_t head(std::int32_t a) const {
    return static_cast<std::int32_t>(arcs_[a].head_slot >> 4);
  }
  std::int32_t sister(std::int32_t a) const {
    const std::uint32_t hs = arcs_[a].head_slot;
    return static_cast<std::int32_t>(hs >> 4) * max_degree_ + static_cast<std::int32_t>(hs & 15u);
  }

  void set_active(std::int32_t i);
  std::int32_t next_active();
  void make_orphan(std::int32_t i);
  std::int32_t grow(std::int32_t i);
  void augment(std::int32_t middle);
  void adopt_orphans();
  void adopt_source_orphan(std::int32_t i);
  void adopt_sink_orphan(std::int32_t i);
  std::int32_t origin_distance(std::int32_t j);

  std::span<Node> nodes_;
  std::span<Arc> arcs_;
  std::span<std::int32_t> orphans_;  // circular FIFO, at most one entry per node
  std::int32_t max_nodes_ = 0;
  int max_degree_ = 0;
  std::int32_t num_nodes_ = 0;
  std::int32_t active_first_ = -1;
  std::int32_t active_last_ = -1;
  std::int32_t orphan_head_ = 0;
  std::int32_t orphan_count_ = 0;
  std::int32_t time_ = 0;
  Flow flow_ = 0;
  std::int64_t augmentations_ = 0;
};

}  // namespace petra
