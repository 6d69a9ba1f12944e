#include "sim/calib/chessboard_grid.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <numeric>

#include "sim/calib/image_sampling.hpp"

namespace petra::calib {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDirectionTolerance = 15.0 * kPi / 180.0;

// Half-direction h of a corner: 0 and 2 along line 0, 1 and 3 along line 1.
Eigen::Vector2d half_direction(const XCorner& c, int h) {
  const double a = c.line_angle[h % 2] + (h >= 2 ? kPi : 0.0);
  return {std::cos(a), std::sin(a)};
}

double line_distance(double a, double b) {  // angle between two lines, [0, pi/2]
  double d = std::fmod(std::abs(a - b), kPi);
  return std::min(d, kPi - d);
}

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

struct Link {
  int to = -1;
  int back = -1;  // half-direction at `to` that points back
};

using Links = std::vector<std::array<Link, 4>>;

Links find_links(const std::vector<XCorner>& corners, ImageView<const float> smooth,
                 double min_contrast) {
  const int n = static_cast<int>(corners.size());
  std::vector<std::array<int, 4>> nearest(static_cast<std::size_t>(n), {-1, -1, -1, -1});
  const double cos_tol = std::cos(kDirectionTolerance);
  for (int a = 0; a < n; ++a)
    for (int h = 0; h < 4; ++h) {
      const Eigen::Vector2d d = half_direction(corners[static_cast<std::size_t>(a)], h);
      double best = 1e300;
      int best_b = -1;
      for (int b = 0; b < n; ++b) {
        if (b == a) continue;
        const Eigen::Vector2d v =
            corners[static_cast<std::size_t>(b)].uv - corners[static_cast<std::size_t>(a)].uv;
        const double dist = v.norm();
        if (dist < 3.0 || dist >= best) continue;
        if (v.dot(d) < cos_tol * dist) continue;
        const double ang = std::atan2(v.y(), v.x());
        const XCorner& cb = corners[static_cast<std::size_t>(b)];
        if (std::min(line_distance(ang, cb.line_angle[0]), line_distance(ang, cb.line_angle[1])) >
            kDirectionTolerance)
          continue;
        best = dist;
        best_b = b;
      }
      if (best_b >= 0 &&
          separates_squares(smooth, corners[static_cast<std::size_t>(a)].uv,
                            corners[static_cast<std::size_t>(best_b)].uv, min_contrast))
        nearest[static_cast<std::size_t>(a)][static_cast<std::size_t>(h)] = best_b;
    }
  // Along a grid line, neighbouring steps differ by perspective only: a link
  // much longer or shorter than the one continuing it on the other side of
  // either end joins two different patterns (e.g. the board and a small
  // chessboard on a monitor behind it).
  auto length = [&](int a, int h) {
    const int b = nearest[static_cast<std::size_t>(a)][static_cast<std::size_t>(h)];
    return b < 0
               ? 0.0
               : (corners[static_cast<std::size_t>(b)].uv - corners[static_cast<std::size_t>(a)].uv)
                     .norm();
  };
  auto steady = [&](int a, int h, double len) {
    const double other = length(a, (h + 2) % 4);
    return other == 0.0 || (len < 2.0 * other && other < 2.0 * len);
  };
  Links links(static_cast<std::size_t>(n));
  for (int a = 0; a < n; ++a)
    for (int h = 0; h < 4; ++h) {
      const int b = nearest[static_cast<std::size_t>(a)][static_cast<std::size_t>(h)];
      if (b < 0 || !steady(a, h, length(a, h))) continue;
      for (int hb = 0; hb < 4; ++hb)
        if (nearest[static_cast<std::size_t>(b)][static_cast<std::size_t>(hb)] == a &&
            steady(b, hb, length(a, h))) {
          links[static_cast<std::size_t>(a)][static_cast<std::size_t>(h)] = {b, hb};
          break;
        }
    }
  return links;
}

// Label steps: 0 = +i, 1 = +j, 2 = -i, 3 = -j.
constexpr int kStep[4][2] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}};

struct Labelled {
  int node;
  int i, j;
};

struct Component {
  std::vector<Labelled> nodes;
  int conflicts = 0;
};

Component grow(const std::vector<XCorner>& corners, const Links& links, int seed,
               std::vector<char>& visited) {
  Component comp;
  const std::size_t n = corners.size();
  std::vector<std::array<int, 4>> label(n, {-1, -1, -1, -1});
  std::vector<int> ci(n, 0), cj(n, 0);
  const XCorner& s = corners[static_cast<std::size_t>(seed)];
  const double orientation = cross(half_direction(s, 0), half_direction(s, 1)) > 0 ? 1.0 : -1.0;
  label[static_cast<std::size_t>(seed)] = {0, 1, 2, 3};
  visited[static_cast<std::size_t>(seed)] = 1;
  std::deque<int> queue{seed};
  comp.nodes.push_back({seed, 0, 0});
  while (!queue.empty()) {
    const int p = queue.front();
    queue.pop_front();
    const std::size_t pp = static_cast<std::size_t>(p);
    for (int h = 0; h < 4; ++h) {
      const Link& l = links[pp][static_cast<std::size_t>(h)];
      if (l.to < 0) continue;
      const int lab = label[pp][static_cast<std::size_t>(h)];
      const int qi = ci[pp] + kStep[lab][0], qj = cj[pp] + kStep[lab][1];
      const std::size_t q = static_cast<std::size_t>(l.to);
      if (visited[q]) {
        if (label[q][0] >= 0 && (ci[q] != qi || cj[q] != qj)) ++comp.conflicts;
        continue;
      }
      const XCorner& cq = corners[q];
      std::array<int, 4>& lq = label[q];
      lq[static_cast<std::size_t>(l.back)] = (lab + 2) % 4;
      lq[static_cast<std::size_t>((l.back + 2) % 4)] = lab;
      const int along = lab % 2;  // 0: i axis, 1: j axis
      const int plus_along = lab < 2 ? (l.back + 2) % 4 : l.back;
      const Eigen::Vector2d e = half_direction(cq, plus_along);
      const int k1 = (l.back + 1) % 4, k3 = (l.back + 3) % 4;
      const Eigen::Vector2d d1 = half_direction(cq, k1);
      int lab1;
      if (along == 0)
        lab1 = (cross(e, d1) * orientation > 0) ? 1 : 3;  // +j : -j
      else
        lab1 = (cross(d1, e) * orientation > 0) ? 0 : 2;  // +i : -i
      lq[static_cast<std::size_t>(k1)] = lab1;
      lq[static_cast<std::size_t>(k3)] = (lab1 + 2) % 4;
      ci[q] = qi;
      cj[q] = qj;
      visited[q] = 1;
      comp.nodes.push_back({l.to, qi, qj});
      queue.push_back(l.to);
    }
  }
  return comp;
}

}  // namespace

int GridLabelling::found() const {
  return static_cast<int>(std::count_if(cell.begin(), cell.end(), [](int c) { return c >= 0; }));
}

bool separates_squares(ImageView<const float> smooth, const Eigen::Vector2d& a,
                       const Eigen::Vector2d& b, double min_contrast) {
  const Eigen::Vector2d v = b - a;
  const Eigen::Vector2d normal = Eigen::Vector2d(-v.y(), v.x()) * 0.25;
  int sign = 0;
  for (double t : {0.3, 0.5, 0.7}) {
    const Eigen::Vector2d m = a + t * v;
    const Eigen::Vector2d l = m + normal, r = m - normal;
    if (!smooth.in_bounds(static_cast<int>(l.x()), static_cast<int>(l.y())) ||
        !smooth.in_bounds(static_cast<int>(r.x()), static_cast<int>(r.y())))
      return false;
    const double diff =
        sample_bilinear(smooth, l.x(), l.y()) - sample_bilinear(smooth, r.x(), r.y());
    if (std::abs(diff) < 0.5 * min_contrast) return false;
    const int s = diff > 0 ? 1 : -1;
    if (sign != 0 && s != sign) return false;
    sign = s;
  }
  return true;
}

GridLabelling label_grid(const std::vector<XCorner>& corners, ImageView<const float> smooth,
                         double min_contrast) {
  GridLabelling best;
  const Links links = find_links(corners, smooth, min_contrast);
  std::vector<int> order(corners.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return corners[static_cast<std::size_t>(a)].contrast >
           corners[static_cast<std::size_t>(b)].contrast;
  });
  std::vector<char> visited(corners.size(), 0);
  for (int seed : order) {
    if (visited[static_cast<std::size_t>(seed)]) continue;
    const auto& ls = links[static_cast<std::size_t>(seed)];
    if (std::any_of(ls.begin(), ls.end(), [](const Link& l) { return l.to < 0; })) continue;
    Component comp = grow(corners, links, seed, visited);
    if (static_cast<int>(comp.nodes.size()) <= best.found()) continue;
    int i0 = 0, i1 = 0, j0 = 0, j1 = 0;
    for (const Labelled& l : comp.nodes) {
      i0 = std::min(i0, l.i);
      i1 = std::max(i1, l.i);
      j0 = std::min(j0, l.j);
      j1 = std::max(j1, l.j);
    }
    GridLabelling g;
    g.width = i1 - i0 + 1;
    g.height = j1 - j0 + 1;
    g.conflicts = comp.conflicts;
    g.cell.assign(static_cast<std::size_t>(g.width) * g.height, -1);
    bool collision = false;
    for (const Labelled& l : comp.nodes) {
      int& c = g.cell[static_cast<std::size_t>(l.j - j0) * g.width + (l.i - i0)];
      if (c >= 0) collision = true;
      c = l.node;
    }
    if (collision) continue;  // links that contradict each other: not a board
    best = std::move(g);
  }
  return best;
}

}  // namespace petra::calib
