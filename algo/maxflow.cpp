#include "algo/maxflow.hpp"

#include <algorithm>

namespace petra {

std::size_t MaxFlow::bytes_needed(std::int32_t max_nodes, int max_degree) {
  if (max_nodes <= 0 || max_degree <= 0) return 0;
  const auto n = static_cast<std::size_t>(max_nodes);
  const auto d = static_cast<std::size_t>(max_degree);
  // Three blocks, each padded for its alignment.
  return n * sizeof(Node) + n * d * sizeof(Arc) + n * sizeof(std::int32_t) + 3 * alignof(Node);
}

Status MaxFlow::init(Arena& arena, std::int32_t max_nodes, int max_degree) {
  if (max_nodes <= 0 || max_nodes >= (1 << 27)) {
    return Error::make(Errc::out_of_range, "maxflow: max_nodes %d outside 1..%d", max_nodes,
                       (1 << 27) - 1);
  }
  if (max_degree <= 0 || max_degree > kMaxDegreeLimit) {
    return Error::make(Errc::out_of_range, "maxflow: max_degree %d outside 1..%d", max_degree,
                       kMaxDegreeLimit);
  }
  auto nodes = arena.allocate<Node>(static_cast<std::size_t>(max_nodes), "maxflow nodes");
  if (!nodes) return nodes.error();
  auto arcs = arena.allocate<Arc>(
      static_cast<std::size_t>(max_nodes) * static_cast<std::size_t>(max_degree), "maxflow arcs");
  if (!arcs) return arcs.error();
  auto orphans =
      arena.allocate<std::int32_t>(static_cast<std::size_t>(max_nodes), "maxflow orphan queue");
  if (!orphans) return orphans.error();
  nodes_ = *nodes;
  arcs_ = *arcs;
  orphans_ = *orphans;
  max_nodes_ = max_nodes;
  max_degree_ = max_degree;
  return reset(0);
}

Status MaxFlow::reset(std::int32_t num_nodes) {
  if (num_nodes < 0 || num_nodes > max_nodes_) {
    return Error::make(Errc::capacity_exceeded, "maxflow: %d nodes requested, budget %d",
                       num_nodes, max_nodes_);
  }
  num_nodes_ = num_nodes;
  const Node blank{kFree, kNotActive, 0, 0, 0, 0, 0, 0};
  std::fill_n(nodes_.data(), num_nodes, blank);
  active_first_ = active_last_ = -1;
  orphan_head_ = orphan_count_ = 0;
  time_ = 0;
  flow_ = 0;
  augmentations_ = 0;
  return ok_status();
}

void MaxFlow::add_terminal_weights(std::int32_t node, Capacity source_cap, Capacity sink_cap) {
  PETRA_ASSERT(node >= 0 && node < num_nodes_ && source_cap >= 0 && sink_cap >= 0);
  Node& n = nodes_[node];
  std::int64_t cs = source_cap;
  std::int64_t ct = sink_cap;
  if (n.tr_cap > 0) {
    cs += n.tr_cap;
  } else {
    ct -= n.tr_cap;
  }
  flow_ += std::min(cs, ct);
  const std::int64_t net = cs - ct;
  PETRA_ASSERT(net < (std::int64_t{1} << 31) && net > -(std::int64_t{1} << 31));
  n.tr_cap = static_cast<Capacity>(net);
}

bool MaxFlow::add_edge(std::int32_t i, std::int32_t j, Capacity cap, Capacity rev_cap) {
  PETRA_ASSERT(i >= 0 && i < num_nodes_ && j >= 0 && j < num_nodes_ && i != j);
  PETRA_ASSERT(cap >= 0 && rev_cap >= 0);
  Node& ni = nodes_[i];
  Node& nj = nodes_[j];
  if (ni.degree >= max_degree_ || nj.degree >= max_degree_) return false;
  const std::uint32_t si = ni.degree++;
  const std::uint32_t sj = nj.degree++;
  arcs_[static_cast<std::size_t>(i) * max_degree_ + si] = {(static_cast<std::uint32_t>(j) << 4) | sj,
                                                           cap};
  arcs_[static_cast<std::size_t>(j) * max_degree_ + sj] = {(static_cast<std::uint32_t>(i) << 4) | si,
                                                           rev_cap};
  return true;
}

void MaxFlow::set_active(std::int32_t i) {
  Node& n = nodes_[i];
  if (n.next != kNotActive) return;
  n.next = i;  // last of the queue points to itself
  if (active_last_ >= 0) {
    nodes_[active_last_].next = i;
  } else {
    active_first_ = i;
  }
  active_last_ = i;
}

// Pops active nodes until one still belongs to a tree.
std::int32_t MaxFlow::next_active() {
  for (;;) {
    const std::int32_t i = active_first_;
    if (i < 0) return -1;
    Node& n = nodes_[i];
    if (n.next == i) {
      active_first_ = active_last_ = -1;
    } else {
      active_first_ = n.next;
    }
    n.next = kNotActive;
    if (n.parent != kFree) return i;
  }
}

void MaxFlow::make_orphan(std::int32_t i) {
  nodes_[i].parent = kOrphan;
  PETRA_ASSERT(orphan_count_ < num_nodes_);
  std::int32_t tail = orphan_head_ + orphan_count_;
  if (tail >= num_nodes_) tail -= num_nodes_;
  orphans_[tail] = i;
  ++orphan_count_;
}

// Grows the tree of node i by one layer; returns the arc joining the two
// trees (oriented source tree -> sink tree) or -1.
std::int32_t MaxFlow::grow(std::int32_t i) {
  const Node& n = nodes_[i];
  const std::int32_t first = i * max_degree_;
  const std::int32_t last = first + n.degree;
  if (n.is_sink == 0) {
    for (std::int32_t a = first; a < last; ++a) {
      if (arcs_[a].r_cap == 0) continue;
      const std::int32_t j = head(a);
      Node& m = nodes_[j];
      if (m.parent == kFree) {
        m.is_sink = 0;
        m.parent = sister(a);
        m.stamp = n.stamp;
        m.dist = n.dist + 1;
        set_active(j);
      } else if (m.is_sink != 0) {
        return a;
      } else if (m.stamp <= n.stamp && m.dist > n.dist) {
        // A shorter route to the source: shorter paths augment faster.
        m.parent = sister(a);
        m.stamp = n.stamp;
        m.dist = n.dist + 1;
      }
    }
  } else {
    for (std::int32_t a = first; a < last; ++a) {
      const std::int32_t s = sister(a);
      if (arcs_[s].r_cap == 0) continue;
      const std::int32_t j = head(a);
      Node& m = nodes_[j];
      if (m.parent == kFree) {
        m.is_sink = 1;
        m.parent = s;
        m.stamp = n.stamp;
        m.dist = n.dist + 1;
        set_active(j);
      } else if (m.is_sink == 0) {
        return s;
      } else if (m.stamp <= n.stamp && m.dist > n.dist) {
        m.parent = s;
        m.stamp = n.stamp;
        m.dist = n.dist + 1;
      }
    }
  }
  return -1;
}

// Pushes the bottleneck along source -> ... -> middle -> ... -> sink; nodes
// whose tree arc saturates become orphans.
void MaxFlow::augment(std::int32_t middle) {
  const std::int32_t s_end = head(sister(middle));
  const std::int32_t t_end = head(middle);
  Capacity b = arcs_[middle].r_cap;
  std::int32_t i = s_end;
  for (std::int32_t a = nodes_[i].parent; a != kTerminal; a = nodes_[i].parent) {
    b = std::min(b, arcs_[sister(a)].r_cap);
    i = head(a);
  }
  b = std::min(b, nodes_[i].tr_cap);
  i = t_end;
  for (std::int32_t a = nodes_[i].parent; a != kTerminal; a = nodes_[i].parent) {
    b = std::min(b, arcs_[a].r_cap);
    i = head(a);
  }
  b = std::min(b, -nodes_[i].tr_cap);

  arcs_[sister(middle)].r_cap += b;
  arcs_[middle].r_cap -= b;
  i = s_end;
  for (std::int32_t a = nodes_[i].parent; a != kTerminal; a = nodes_[i].parent) {
    const std::int32_t s = sister(a);
    arcs_[a].r_cap += b;
    arcs_[s].r_cap -= b;
    const std::int32_t up = head(a);
    if (arcs_[s].r_cap == 0) make_orphan(i);
    i = up;
  }
  nodes_[i].tr_cap -= b;
  if (nodes_[i].tr_cap == 0) make_orphan(i);
  i = t_end;
  for (std::int32_t a = nodes_[i].parent; a != kTerminal; a = nodes_[i].parent) {
    const std::int32_t s = sister(a);
    arcs_[s].r_cap += b;
    arcs_[a].r_cap -= b;
    const std::int32_t up = head(a);
    if (arcs_[a].r_cap == 0) make_orphan(i);
    i = up;
  }
  nodes_[i].tr_cap += b;
  if (nodes_[i].tr_cap == 0) make_orphan(i);
  flow_ += b;
  ++augmentations_;
}

// Distance from j to its terminal along tree arcs, or kNoDist when the path
// meets an orphan. Valid paths are stamped with the current time so later
// checks stop early.
std::int32_t MaxFlow::origin_distance(std::int32_t j) {
  std::int32_t d = 0;
  std::int32_t k = j;
  for (;;) {
    Node& n = nodes_[k];
    if (n.stamp == time_) {
      d += n.dist;
      break;
    }
    const std::int32_t a = n.parent;
    ++d;
    if (a == kTerminal) {
      n.stamp = time_;
      n.dist = 1;
      break;
    }
    if (a < 0) return kNoDist;  // an orphan on the way
    k = head(a);
  }
  const std::int32_t total = d;
  for (k = j; nodes_[k].stamp != time_; k = head(nodes_[k].parent)) {
    nodes_[k].stamp = time_;
    nodes_[k].dist = d--;
  }
  return total;
}

void MaxFlow::adopt_source_orphan(std::int32_t i) {
  const std::int32_t first = i * max_degree_;
  const std::int32_t last = first + nodes_[i].degree;
  std::int32_t best = -1;
  std::int32_t best_dist = kNoDist;
  for (std::int32_t a = first; a < last; ++a) {
    if (arcs_[sister(a)].r_cap == 0) continue;
    const std::int32_t j = head(a);
    const Node& m = nodes_[j];
    if (m.is_sink != 0 || m.parent == kFree) continue;
    const std::int32_t d = origin_distance(j);
    if (d < best_dist) {
      best = a;
      best_dist = d;
    }
  }
  if (best >= 0) {
    nodes_[i].parent = best;
    nodes_[i].stamp = time_;
    nodes_[i].dist = best_dist + 1;
    return;
  }
  // No way back to the source: i leaves the tree, its children are orphaned and
  // the neighbours that could reach it again are re-activated.
  for (std::int32_t a = first; a < last; ++a) {
    const std::int32_t j = head(a);
    const Node& m = nodes_[j];
    if (m.is_sink != 0 || m.parent == kFree) continue;
    if (arcs_[sister(a)].r_cap > 0) set_active(j);
    if (m.parent >= 0 && head(m.parent) == i) make_orphan(j);
  }
  nodes_[i].parent = kFree;
}

void MaxFlow::adopt_sink_orphan(std::int32_t i) {
  const std::int32_t first = i * max_degree_;
  const std::int32_t last = first + nodes_[i].degree;
  std::int32_t best = -1;
  std::int32_t best_dist = kNoDist;
  for (std::int32_t a = first; a < last; ++a) {
    if (arcs_[a].r_cap == 0) continue;
    const std::int32_t j = head(a);
    const Node& m = nodes_[j];
    if (m.is_sink == 0 || m.parent == kFree) continue;
    const std::int32_t d = origin_distance(j);
    if (d < best_dist) {
      best = a;
      best_dist = d;
    }
  }
  if (best >= 0) {
    nodes_[i].parent = best;
    nodes_[i].stamp = time_;
    nodes_[i].dist = best_dist + 1;
    return;
  }
  for (std::int32_t a = first; a < last; ++a) {
    const std::int32_t j = head(a);
    const Node& m = nodes_[j];
    if (m.is_sink == 0 || m.parent == kFree) continue;
    if (arcs_[a].r_cap > 0) set_active(j);
    if (m.parent >= 0 && head(m.parent) == i) make_orphan(j);
  }
  nodes_[i].parent = kFree;
}

void MaxFlow::adopt_orphans() {
  while (orphan_count_ > 0) {
    const std::int32_t i = orphans_[orphan_head_];
    if (++orphan_head_ == num_nodes_) orphan_head_ = 0;
    --orphan_count_;
    if (nodes_[i].is_sink != 0) {
      adopt_sink_orphan(i);
    } else {
      adopt_source_orphan(i);
    }
  }
}

MaxFlow::Flow MaxFlow::solve() {
  active_first_ = active_last_ = -1;
  orphan_head_ = orphan_count_ = 0;
  time_ = 0;
  augmentations_ = 0;
  for (std::int32_t i = 0; i < num_nodes_; ++i) {
    Node& n = nodes_[i];
    n.next = kNotActive;
    n.stamp = 0;
    n.dist = 1;
    if (n.tr_cap != 0) {
      n.is_sink = static_cast<std::uint8_t>(n.tr_cap < 0);
      n.parent = kTerminal;
      set_active(i);
    } else {
      n.parent = kFree;
    }
  }
  std::int32_t current = -1;  // keeps growing from the node that found the last path
  for (;;) {
    std::int32_t i = current;
    if (i >= 0) {
      nodes_[i].next = kNotActive;
      if (nodes_[i].parent == kFree) i = -1;
    }
    if (i < 0) {
      i = next_active();
      if (i < 0) break;
    }
    const std::int32_t middle = grow(i);
    if (middle < 0) {
      current = -1;
      continue;
    }
    nodes_[i].next = i;  // counts as active while we augment, so it is not queued twice
    current = i;
    ++time_;
    augment(middle);
    adopt_orphans();
  }
  return flow_;
}

}  // namespace petra
