// Max-flow / min-cut on a directed graph with source and sink terminals, by the
// Boykov-Kolmogorov method: two search trees (one grown from each terminal)
// are kept between augmentations and repaired after each one instead of being
// rebuilt, which suits the short-path, grid-like graphs of vision problems.
//
// Inputs:  nodes 0..n-1, terminal capacities per node, edges (i, j, cap, rev_cap),
//          integer capacities >= 0 (use kInfiniteCapacity for hard constraints).
// Outputs: the maximum flow value (= minimum cut cost) and, per node, its side
//          of a minimum cut (source side unless it can still reach the sink).
// Memory:  from an Arena at init, for a maximum node count:
//          bytes_needed(n) = n * (sizeof(Record) + 9) + alignment, where a
//          Record holds a node (16 B) and its kMaxDegree arc slots (8 B each):
//          64 B for the degree-6 graphs of the graph-cut matcher.
//          reset()/add_*()/solve() never allocate, so one solver serves every
//          graph of a run (e.g. each alpha-expansion of the graph-cut matcher).
// Layout:  a node and its arcs share one record (one cache line at degree 6):
//          growing a tree from a node and checking a neighbour's reverse arc
//          each touch a single line. Arc ids are (node << 3 | slot), and an
//          arc stores its sister's id, so reverse arcs cost no lookup.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "algo/core/arena.hpp"
#include "algo/core/result.hpp"

namespace petra {

template <int kMaxDegree>
class MaxFlow {
  static_assert(kMaxDegree >= 1 && kMaxDegree <= 8, "arc ids keep 3 bits for the slot");

 public:
  using Capacity = std::int32_t;
  using Flow = std::int64_t;

  // Large enough that no finite cut reaches it in the graphs we build, small
  // enough that residual updates never overflow int32.
  static constexpr Capacity kInfiniteCapacity = 1 << 29;
  static constexpr std::int32_t kMaxNodes = (1 << 27) - 1;

  static std::size_t bytes_needed(std::int32_t max_nodes);

  // Takes its storage from `arena` (errors: node count out of range, arena too small).
  Status init(Arena& arena, std::int32_t max_nodes);

  // Starts a new graph of `num_nodes` isolated nodes with zero capacities.
  Status reset(std::int32_t num_nodes);

  // Appends one isolated node and returns its id (the caller keeps within
  // max_nodes: asserted). With reset(0), graphs can be built node by node.
  std::int32_t add_node() {
    PETRA_ASSERT(num_nodes_ < max_nodes_);
    const std::int32_t i = num_nodes_++;
    Record& r = records_[i];
    r.node = Node{kFree, 0, 0, 0};
    // Unused slots point back to themselves with no capacity: loops scan
    // every slot, with no degree test in the hot paths.
    for (int s = 0; s < kMaxDegree; ++s)
      r.arcs[s] = Arc{static_cast<std::uint32_t>(arc_id(i, s)), 0};
    degree_[i] = 0;
    return i;
  }

  // Adds capacity source->node and node->sink (both >= 0). Opposite terminal
  // capacities cancel at once (their common part is flow already sent).
  void add_terminal_weights(std::int32_t node, Capacity source_cap, Capacity sink_cap) {
    PETRA_ASSERT(static_cast<std::uint32_t>(node) < static_cast<std::uint32_t>(num_nodes_) &&
                 (source_cap | sink_cap) >= 0);
    Node& n = records_[node].node;
    std::int64_t cs = source_cap;
    std::int64_t ct = sink_cap;
    if (n.tr_cap > 0) {
      cs += n.tr_cap;
    } else {
      ct -= n.tr_cap;
    }
    flow_ += cs < ct ? cs : ct;
    const std::int64_t net = cs - ct;
    PETRA_ASSERT(net < (std::int64_t{1} << 31) && net > -(std::int64_t{1} << 31));
    sink_links_ += (net < 0 ? 1 : 0) - (n.tr_cap < 0 ? 1 : 0);
    n.tr_cap = static_cast<Capacity>(net);
  }

  // Adds arc i->j with capacity `cap` and arc j->i with `rev_cap` (i != j).
  // Each call uses one edge slot of i and one of j: returns false, and changes
  // nothing, when either node already has kMaxDegree slots in use.
  [[nodiscard]] bool add_edge(std::int32_t i, std::int32_t j, Capacity cap, Capacity rev_cap) {
    PETRA_ASSERT(static_cast<std::uint32_t>(i) < static_cast<std::uint32_t>(num_nodes_) &&
                 static_cast<std::uint32_t>(j) < static_cast<std::uint32_t>(num_nodes_) && i != j &&
                 (cap | rev_cap) >= 0);
    const int si = degree_[i];
    const int sj = degree_[j];
    if (si >= kMaxDegree || sj >= kMaxDegree) return false;
    degree_[i] = static_cast<std::uint8_t>(si + 1);
    degree_[j] = static_cast<std::uint8_t>(sj + 1);
    records_[i].arcs[si] = Arc{static_cast<std::uint32_t>(arc_id(j, sj)), cap};
    records_[j].arcs[sj] = Arc{static_cast<std::uint32_t>(arc_id(i, si)), rev_cap};
    return true;
  }

  // Search policy (defaults suit the graph-cut matcher; tests vary them to
  // reach every path): grow only the tree of the terminal with fewer links
  // when the other has more than `ratio` times as many (0: always both), and
  // fall back to both trees after `orphan_budget` orphans per node.
  void set_search_policy(int ratio, int orphan_budget) {
    one_sided_ratio_ = ratio;
    orphan_budget_ = orphan_budget;
  }

  // Computes the maximum flow of the current graph (call once per reset).
  Flow solve();

  // After solve(): true when the node is on the sink side of the minimum cut.
  // Free nodes (in neither tree) go with the terminal whose tree was not
  // grown to completion: the grown tree is the closed one.
  bool in_sink_side(std::int32_t node) const {
    const Node& n = records_[node].node;
    return n.parent == kFree ? !grow_sink_ : (n.bits & kSinkBit) != 0;
  }

  std::int32_t num_nodes() const { return num_nodes_; }
  std::int32_t max_nodes() const { return max_nodes_; }
  int degree(std::int32_t node) const { return degree_[node]; }
  // Augmenting paths found by the tree search in the last solve() (a measure of its work).
  std::int64_t augmentations() const { return augmentations_; }

 private:
  // Parent codes (arc ids are >= 0).
  static constexpr std::int32_t kFree = -1;      // in no tree
  static constexpr std::int32_t kTerminal = -2;  // child of its terminal
  static constexpr std::int32_t kOrphan = -3;    // lost its parent, pending adoption
  static constexpr std::uint32_t kSinkBit = 1u;
  static constexpr std::uint32_t kActiveBit = 2u;
  static constexpr std::int32_t kNoDist = 1 << 29;

  struct Node {
    std::int32_t parent;  // arc from this node to its parent in its tree, or a code
    Capacity tr_cap;      // > 0: residual source->node, < 0: residual node->sink
    std::int32_t stamp;   // time its distance to the terminal was last verified
    std::uint32_t bits;   // distance to the terminal << 2 | kActiveBit | kSinkBit
    std::int32_t dist() const { return static_cast<std::int32_t>(bits >> 2); }
    void set_dist(std::int32_t d) { bits = (static_cast<std::uint32_t>(d) << 2) | (bits & 3u); }
    bool is_sink() const { return (bits & kSinkBit) != 0; }
  };
  struct Arc {
    std::uint32_t sister;  // id of the reverse arc; its node is the head of this one
    Capacity r_cap;
  };
  static constexpr std::size_t kRecordBytes = sizeof(Node) + kMaxDegree * sizeof(Arc);
  struct alignas(kRecordBytes % 64 == 0 ? 64 : 16) Record {
    Node node;
    Arc arcs[kMaxDegree];
  };

  Arc& arc(std::int32_t id) { return records_[id >> 3].arcs[id & 7]; }
  static std::int32_t head_of(const Arc& a) { return static_cast<std::int32_t>(a.sister >> 3); }
  static std::int32_t arc_id(std::int32_t node, int slot) { return (node << 3) | slot; }

  void set_active(std::int32_t i);
  std::int32_t next_active();
  void make_orphan(std::int32_t i, bool front);
  void push_short_paths(std::int32_t& sources, std::int32_t& sinks);
  std::int32_t grow(std::int32_t i);
  void augment(std::int32_t middle);
  void adopt_orphans();
  template <bool kSink>
  void adopt(std::int32_t i);
  std::int32_t origin_distance(std::int32_t j);

  std::span<Record> records_;
  std::span<std::uint8_t> degree_;   // slots in use per node
  std::span<std::int32_t> active_;   // circular FIFO of active nodes
  std::span<std::int32_t> orphans_;  // circular FIFO of orphans
  std::int32_t max_nodes_ = 0;
  std::int32_t num_nodes_ = 0;
  std::int32_t active_head_ = 0;
  std::int32_t active_count_ = 0;
  std::int32_t orphan_head_ = 0;
  std::int32_t orphan_count_ = 0;
  std::int32_t time_ = 0;
  bool grow_source_ = true;
  bool grow_sink_ = true;
  Flow flow_ = 0;
  std::int32_t sink_links_ = 0;  // nodes with tr_cap < 0, kept by add_terminal_weights()
  std::int64_t augmentations_ = 0;
  std::int64_t orphans_seen_ = 0;
  // Measured on the graph-cut matcher's default configuration
  // (docs/graphcut.md, "Max-flow solver").
  int one_sided_ratio_ = 32;
  int orphan_budget_ = 3;
};

extern template class MaxFlow<2>;
extern template class MaxFlow<4>;
extern template class MaxFlow<6>;
extern template class MaxFlow<8>;

}  // namespace petra
