#include "algo/stereo/maxflow.hpp"

#include <algorithm>

namespace petra {

template <int D>
std::size_t MaxFlow<D>::bytes_needed(std::int32_t max_nodes) {
  if (max_nodes <= 0) return 0;
  const auto n = static_cast<std::size_t>(max_nodes);
  return n * (sizeof(Record) + 1 + 2 * sizeof(std::int32_t)) + 4 * alignof(Record);
}

template <int D>
Status MaxFlow<D>::init(Arena& arena, std::int32_t max_nodes) {
  if (max_nodes <= 0 || max_nodes > kMaxNodes) {
    return Error::make(Errc::out_of_range, "maxflow: max_nodes %d outside 1..%d", max_nodes,
                       kMaxNodes);
  }
  const auto n = static_cast<std::size_t>(max_nodes);
  auto records = arena.allocate<Record>(n, "maxflow nodes");
  if (!records) return records.error();
  auto degree = arena.allocate<std::uint8_t>(n, "maxflow degrees");
  if (!degree) return degree.error();
  auto active = arena.allocate<std::int32_t>(n, "maxflow active queue");
  if (!active) return active.error();
  auto orphans = arena.allocate<std::int32_t>(n, "maxflow orphan queue");
  if (!orphans) return orphans.error();
  records_ = *records;
  degree_ = *degree;
  active_ = *active;
  orphans_ = *orphans;
  max_nodes_ = max_nodes;
  return reset(0);
}

template <int D>
Status MaxFlow<D>::reset(std::int32_t num_nodes) {
  if (num_nodes < 0 || num_nodes > max_nodes_) {
    return Error::make(Errc::capacity_exceeded, "maxflow: %d nodes requested, budget %d", num_nodes,
                       max_nodes_);
  }
  num_nodes_ = 0;
  active_head_ = active_count_ = 0;
  orphan_head_ = orphan_count_ = 0;
  time_ = 0;
  flow_ = 0;
  sink_links_ = 0;
  augmentations_ = 0;
  for (std::int32_t i = 0; i < num_nodes; ++i) (void)add_node();
  return ok_status();
}

template <int D>
void MaxFlow<D>::set_active(std::int32_t i) {
  Node& n = records_[i].node;
  if ((n.bits & kActiveBit) != 0) return;
  if (n.is_sink() ? !grow_sink_ : !grow_source_) return;  // that tree stays as it is
  n.bits |= kActiveBit;
  std::int32_t tail = active_head_ + active_count_;
  if (tail >= num_nodes_) tail -= num_nodes_;
  active_[tail] = i;
  ++active_count_;
}

// Pops active nodes until one still belongs to a tree.
template <int D>
std::int32_t MaxFlow<D>::next_active() {
  while (active_count_ > 0) {
    const std::int32_t i = active_[active_head_];
    if (++active_head_ == num_nodes_) active_head_ = 0;
    --active_count_;
    Node& n = records_[i].node;
    n.bits &= ~kActiveBit;
    if (n.parent != kFree) return i;
  }
  return -1;
}

// Orphans of an augmentation go to the front, the one nearest its terminal
// first: once it has a parent again, the orphans below it can reach the
// terminal through it instead of being freed. Orphans found while adopting
// go to the back.
template <int D>
void MaxFlow<D>::make_orphan(std::int32_t i, bool front) {
  records_[i].node.parent = kOrphan;
  ++orphans_seen_;
  PETRA_ASSERT(orphan_count_ < num_nodes_);
  if (front) {
    orphan_head_ = orphan_head_ == 0 ? num_nodes_ - 1 : orphan_head_ - 1;
    orphans_[orphan_head_] = i;
  } else {
    std::int32_t tail = orphan_head_ + orphan_count_;
    if (tail >= num_nodes_) tail -= num_nodes_;
    orphans_[tail] = i;
  }
  ++orphan_count_;
}

// Sends flow along every path source -> i -> j -> sink that the terminal links
// allow, before any search: in the matcher's graphs much of the flow takes
// such two-node paths (a current match and a competing new one), and one pass
// in node order is far cheaper than one tree search per path.
//
// It also counts the nodes left linked to each terminal (solve() chooses the
// trees to grow from them) without another pass over the nodes: a source
// node's capacity is final after its own turn, and a sink node leaves the
// count when a push empties it.
template <int D>
void MaxFlow<D>::push_short_paths(std::int32_t& sources, std::int32_t& sinks) {
  sources = 0;
  sinks = 0;
  sinks = sink_links_;
  for (std::int32_t i = 0; i < num_nodes_; ++i) {
    Record& r = records_[i];
    if (r.node.tr_cap <= 0) continue;
    for (int s = 0; s < D && r.node.tr_cap > 0; ++s) {
      Arc& a = r.arcs[s];
      if (a.r_cap == 0) continue;
      Node& m = records_[head_of(a)].node;
      if (m.tr_cap >= 0) continue;
      const Capacity f = std::min({r.node.tr_cap, a.r_cap, -m.tr_cap});
      r.node.tr_cap -= f;
      m.tr_cap += f;
      a.r_cap -= f;
      arc(static_cast<std::int32_t>(a.sister)).r_cap += f;
      flow_ += f;
      sinks -= m.tr_cap == 0 ? 1 : 0;
    }
    sources += r.node.tr_cap > 0 ? 1 : 0;
  }
}

// Grows the tree of node i by one layer; returns the arc joining the two
// trees (oriented source tree -> sink tree) or -1.
template <int D>
std::int32_t MaxFlow<D>::grow(std::int32_t i) {
  Record& r = records_[i];
  const Node& n = r.node;
  const std::int32_t child_dist = n.dist() + 1;
  if (!n.is_sink()) {
    for (int s = 0; s < D; ++s) {
      const Arc& a = r.arcs[s];
      if (a.r_cap == 0) continue;
      const std::int32_t j = head_of(a);
      Node& m = records_[j].node;
      if (m.parent == kFree) {
        m.bits &= ~kSinkBit;
        m.parent = static_cast<std::int32_t>(a.sister);
        m.stamp = n.stamp;
        m.set_dist(child_dist);
        set_active(j);
      } else if (m.is_sink()) {
        return arc_id(i, s);
      } else if (m.stamp <= n.stamp && m.dist() > n.dist()) {
        // A shorter route to the source: shorter paths augment faster.
        m.parent = static_cast<std::int32_t>(a.sister);
        m.stamp = n.stamp;
        m.set_dist(child_dist);
      }
    }
  } else {
    for (int s = 0; s < D; ++s) {
      const Arc& a = r.arcs[s];
      const std::int32_t j = head_of(a);
      Record& rj = records_[j];
      const Arc& back = rj.arcs[a.sister & 7];  // j -> i, in j's own record
      if (back.r_cap == 0) continue;
      Node& m = rj.node;
      if (m.parent == kFree) {
        m.bits |= kSinkBit;
        m.parent = static_cast<std::int32_t>(a.sister);
        m.stamp = n.stamp;
        m.set_dist(child_dist);
        set_active(j);
      } else if (!m.is_sink()) {
        return static_cast<std::int32_t>(a.sister);
      } else if (m.stamp <= n.stamp && m.dist() > n.dist()) {
        m.parent = static_cast<std::int32_t>(a.sister);
        m.stamp = n.stamp;
        m.set_dist(child_dist);
      }
    }
  }
  return -1;
}

// Pushes the bottleneck along source -> ... -> middle -> ... -> sink; nodes
// whose tree arc saturates become orphans.
template <int D>
void MaxFlow<D>::augment(std::int32_t middle) {
  Arc& mid = arc(middle);
  const std::int32_t s_end = middle >> 3;
  const std::int32_t t_end = head_of(mid);
  Capacity b = mid.r_cap;
  std::int32_t i = s_end;
  for (std::int32_t a = records_[i].node.parent; a != kTerminal; a = records_[i].node.parent) {
    b = std::min(b, arc(static_cast<std::int32_t>(arc(a).sister)).r_cap);
    i = head_of(arc(a));
  }
  b = std::min(b, records_[i].node.tr_cap);
  i = t_end;
  for (std::int32_t a = records_[i].node.parent; a != kTerminal; a = records_[i].node.parent) {
    b = std::min(b, arc(a).r_cap);
    i = head_of(arc(a));
  }
  b = std::min(b, -records_[i].node.tr_cap);

  arc(static_cast<std::int32_t>(mid.sister)).r_cap += b;
  mid.r_cap -= b;
  i = s_end;
  for (std::int32_t a = records_[i].node.parent; a != kTerminal; a = records_[i].node.parent) {
    Arc& up = arc(a);
    Arc& down = arc(static_cast<std::int32_t>(up.sister));
    up.r_cap += b;
    down.r_cap -= b;
    const std::int32_t parent = head_of(up);
    if (down.r_cap == 0) make_orphan(i, true);
    i = parent;
  }
  records_[i].node.tr_cap -= b;
  if (records_[i].node.tr_cap == 0) make_orphan(i, true);
  i = t_end;
  for (std::int32_t a = records_[i].node.parent; a != kTerminal; a = records_[i].node.parent) {
    Arc& up = arc(a);
    arc(static_cast<std::int32_t>(up.sister)).r_cap += b;
    up.r_cap -= b;
    const std::int32_t parent = head_of(up);
    if (up.r_cap == 0) make_orphan(i, true);
    i = parent;
  }
  records_[i].node.tr_cap += b;
  if (records_[i].node.tr_cap == 0) make_orphan(i, true);
  flow_ += b;
  ++augmentations_;
}

// Distance from j to its terminal along tree arcs, or kNoDist when the path
// meets an orphan. Valid paths are stamped with the current time so later
// checks stop early.
template <int D>
std::int32_t MaxFlow<D>::origin_distance(std::int32_t j) {
  std::int32_t d = 0;
  std::int32_t k = j;
  for (;;) {
    Node& n = records_[k].node;
    if (n.stamp == time_) {
      d += n.dist();
      break;
    }
    const std::int32_t a = n.parent;
    ++d;
    if (a == kTerminal) {
      n.stamp = time_;
      n.set_dist(1);
      break;
    }
    if (a < 0) return kNoDist;  // an orphan on the way
    k = head_of(arc(a));
  }
  const std::int32_t total = d;
  for (k = j; records_[k].node.stamp != time_; k = head_of(arc(records_[k].node.parent))) {
    records_[k].node.stamp = time_;
    records_[k].node.set_dist(d--);
  }
  return total;
}

// Finds a new parent for orphan i in its own tree (one whose path still
// reaches the terminal, preferring the shortest), or frees it.
template <int D>
template <bool kSink>
void MaxFlow<D>::adopt(std::int32_t i) {
  Record& r = records_[i];
  std::int32_t best = -1;
  std::int32_t best_dist = kNoDist;
  // A tree that does not grow only marks the nodes its terminal feeds
  // directly; an orphan of it is simply freed (the growing tree finds a
  // route through it if there is one).
  const bool own_tree_grows = kSink ? grow_sink_ : grow_source_;
  for (int s = 0; s < (own_tree_grows ? D : 0); ++s) {
    const Arc& a = r.arcs[s];
    const std::int32_t j = head_of(a);
    Record& rj = records_[j];
    // Source tree: flow would come j -> i; sink tree: i -> j.
    const Capacity residual = kSink ? a.r_cap : rj.arcs[a.sister & 7].r_cap;
    if (residual == 0) continue;
    const Node& m = rj.node;
    if (m.is_sink() != kSink || m.parent == kFree) continue;
    const std::int32_t d = origin_distance(j);
    if (d < best_dist) {
      best = arc_id(i, s);
      best_dist = d;
    }
  }
  if (best >= 0) {
    r.node.parent = best;
    r.node.stamp = time_;
    r.node.set_dist(best_dist + 1);
    return;
  }
  // No way back to the terminal: i leaves the tree, its children are orphaned
  // and the neighbours that could take it in again are re-activated. When
  // only the other tree grows, that tree must be able to take i in instead.
  for (int s = 0; s < D; ++s) {
    const Arc& a = r.arcs[s];
    const std::int32_t j = head_of(a);
    if (j == i) continue;  // unused slot
    Record& rj = records_[j];
    const Node& m = rj.node;
    if (m.parent == kFree) continue;
    const Capacity into_i = rj.arcs[a.sister & 7].r_cap;  // j -> i
    if (m.is_sink() == kSink) {
      if ((kSink ? a.r_cap : into_i) > 0) set_active(j);
      if (m.parent >= 0 && head_of(arc(m.parent)) == i) make_orphan(j, false);
    } else if (!own_tree_grows && (kSink ? into_i : a.r_cap) > 0) {
      set_active(j);
    }
  }
  r.node.parent = kFree;
}

template <int D>
void MaxFlow<D>::adopt_orphans() {
  while (orphan_count_ > 0) {
    const std::int32_t i = orphans_[orphan_head_];
    if (++orphan_head_ == num_nodes_) orphan_head_ = 0;
    --orphan_count_;
    if (records_[i].node.is_sink()) {
      adopt<true>(i);
    } else {
      adopt<false>(i);
    }
  }
}

template <int D>
typename MaxFlow<D>::Flow MaxFlow<D>::solve() {
  std::int32_t sources = 0;
  std::int32_t sinks = 0;
  push_short_paths(sources, sinks);
  active_head_ = active_count_ = 0;
  orphan_head_ = orphan_count_ = 0;
  time_ = 0;
  augmentations_ = 0;
  orphans_seen_ = 0;
  // Which trees to grow. When one terminal keeps far fewer links than the
  // other, only its tree is grown: a path is found as soon as it touches a
  // node of the other terminal, and the large tree (often the whole graph)
  // is never built. Both ways end with one tree closed, so the cut is minimum.
  const std::int64_t ratio = one_sided_ratio_;
  grow_source_ = ratio == 0 || sources <= ratio * sinks;
  grow_sink_ = ratio == 0 || sinks <= ratio * sources;
  for (std::int32_t i = 0; i < num_nodes_; ++i) {
    Node& n = records_[i].node;
    n.stamp = 0;
    if (n.tr_cap != 0) {
      const bool sink = n.tr_cap < 0;
      n.bits = (1u << 2) | (sink ? kSinkBit : 0u);
      n.parent = kTerminal;
      if (sink ? grow_sink_ : grow_source_) set_active(i);
    } else {
      n.bits = 0;
      n.parent = kFree;
    }
  }
  std::int32_t current = -1;  // keeps growing from the node that found the last path
  for (;;) {
    std::int32_t i = current;
    if (i >= 0) {
      records_[i].node.bits &= ~kActiveBit;
      if (records_[i].node.parent == kFree) i = -1;
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
    records_[i].node.bits |= kActiveBit;  // not queued twice while we augment
    current = i;
    ++time_;
    augment(middle);
    adopt_orphans();
    // A lone tree with few roots can be deep, and saturating a root then
    // orphans it wholesale, again and again. Past a budget of orphans, let
    // the other tree grow too (every node of it is activated, which is all
    // the two-tree search needs to stay exact).
    if ((!grow_source_ || !grow_sink_) &&
        orphans_seen_ > orphan_budget_ * static_cast<std::int64_t>(num_nodes_)) {
      grow_source_ = grow_sink_ = true;
      for (std::int32_t k = 0; k < num_nodes_; ++k) {
        if (records_[k].node.parent != kFree) set_active(k);
      }
    }
  }
  return flow_;
}

template class MaxFlow<2>;
template class MaxFlow<4>;
template class MaxFlow<6>;
template class MaxFlow<8>;

}  // namespace petra
