#include "algo/propose/rock_split.hpp"

#include <algorithm>
#include <utility>

namespace petra {

namespace {

// The part's peak point (path halving: no recursion, no heap).
std::int32_t find(std::span<std::int32_t> part, std::int32_t i) {
  while (part[static_cast<std::size_t>(i)] != i) {
    const std::size_t k = static_cast<std::size_t>(i);
    part[k] = part[static_cast<std::size_t>(part[k])];
    i = part[k];
  }
  return i;
}

struct Flood {
  const SplitGrid& grid;
  std::span<const float> height;
  const SplitParams& p;
  std::span<std::int32_t> part;
  std::span<std::int32_t> size;  // points per part, at its peak point

  float peak(std::int32_t root) const { return height[static_cast<std::size_t>(root)]; }
  // Whether part a's peak ranks below part b's (ties: the later point).
  bool lower(std::int32_t a, std::int32_t b) const {
    return peak(a) < peak(b) || (peak(a) == peak(b) && a > b);
  }
  void join(std::int32_t lo, std::int32_t hi) {
    part[static_cast<std::size_t>(lo)] = hi;
    size[static_cast<std::size_t>(hi)] += size[static_cast<std::size_t>(lo)];
  }

  // Point i (all higher points seen): joins its highest seen neighbour's
  // part, then merges the other parts it touches unless they stay apart.
  void add(std::int32_t i) {
    const std::size_t k = static_cast<std::size_t>(i);
    part[k] = i;
    size[k] = 1;
    const int x = grid.pixels[k].u, y = grid.pixels[k].v;
    std::int32_t seen[8];
    int n = 0;
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const int nx = x + dx, ny = y + dy;
        if ((dx == 0 && dy == 0) || nx < 0 || ny < 0 || nx >= grid.w || ny >= grid.h) continue;
        const std::int32_t j =
            grid.index[static_cast<std::size_t>(ny) * static_cast<std::size_t>(grid.w) +
                       static_cast<std::size_t>(nx)];
        if (j >= 0 && j != i && part[static_cast<std::size_t>(j)] != kNoSplitPart) seen[n++] = j;
      }
    if (n == 0) return;          // a local maximum: a part of its own
    for (int m = 1; m < n; ++m)  // the highest neighbour first
      if (height[static_cast<std::size_t>(seen[m])] > height[static_cast<std::size_t>(seen[0])])
        std::swap(seen[0], seen[m]);
    join(i, find(part, seen[0]));
    for (int m = 1; m < n; ++m) {
      const std::int32_t a = find(part, i), b = find(part, seen[m]);
      if (a == b) continue;
      const std::int32_t lo = lower(a, b) ? a : b, hi = lo == a ? b : a;
      const bool apart = static_cast<double>(peak(lo) - height[k]) >= p.prominence_mm &&
                         size[static_cast<std::size_t>(lo)] >= p.min_pixels;
      if (!apart) join(lo, hi);
    }
  }
};

}  // namespace

Status split_at_saddles(const SplitGrid& grid, std::span<const float> height,
                        std::span<const PointClass> labels, const SplitParams& p,
                        std::span<std::int32_t> part, std::span<std::int32_t> order,
                        std::span<std::int32_t> sizes) {
  const std::size_t n = labels.size();
  if (height.size() != n || part.size() != n || order.size() != n || sizes.size() != n ||
      grid.pixels.size() != n ||
      grid.index.size() != static_cast<std::size_t>(grid.w) * static_cast<std::size_t>(grid.h))
    return Error::make(Errc::invalid_argument, "split: %zu labels, %zu heights, %zu parts", n,
                       height.size(), part.size());
  std::size_t m = 0;
  for (std::size_t i = 0; i < n; ++i) {
    part[i] = kNoSplitPart;
    if (labels[i] == PointClass::rock) order[m++] = static_cast<std::int32_t>(i);
  }
  const auto by_height = [&](std::int32_t a, std::int32_t b) {
    const float ha = height[static_cast<std::size_t>(a)], hb = height[static_cast<std::size_t>(b)];
    return ha > hb || (ha == hb && a < b);
  };
  std::sort(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(m), by_height);
  Flood flood{grid, height, p, part, sizes};
  for (std::size_t k = 0; k < m; ++k) flood.add(order[k]);
  for (std::size_t k = 0; k < m; ++k) {
    const std::int32_t i = order[k];
    part[static_cast<std::size_t>(i)] = find(part, i);
  }
  return {};
}

}  // namespace petra
