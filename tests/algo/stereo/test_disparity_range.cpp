#include "algo/stereo/disparity_range.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <string>
#include <vector>

namespace petra {
namespace {

// A textured fronto-parallel pair: the right view is the left shifted by d.
struct RangePair {
  int w = 640, h = 300;
  std::vector<std::uint8_t> left, right;
  explicit RangePair(int d) : left(static_cast<std::size_t>(w) * h), right(left.size()) {
    std::mt19937 rng(7);
    std::vector<int> noise(static_cast<std::size_t>(w + d) * h);
    for (auto& v : noise) v = static_cast<int>(rng() % 256);
    // 9x9 box blur, contrast stretched: texture at the scale of rock and
    // soil grain in the simulator's images, still there at 1/4 resolution.
    auto tex = [&](int x, int y) {
      int s = 0, n = 0;
      for (int dy = -4; dy <= 4; ++dy)
        for (int dx = -4; dx <= 4; ++dx) {
          const int xx = std::clamp(x + dx, 0, w + d - 1), yy = std::clamp(y + dy, 0, h - 1);
          s += noise[static_cast<std::size_t>(yy) * (w + d) + xx];
          ++n;
        }
      return static_cast<std::uint8_t>(std::clamp(128 + 6 * (s / n - 128), 0, 255));
    };
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        left[static_cast<std::size_t>(y) * w + x] = tex(x, y);
        right[static_cast<std::size_t>(y) * w + x] = tex(x + d, y);  // left(x) = right(x - d)
      }
  }
  ConstGray8View l() const { return {left.data(), w, h}; }
  ConstGray8View r() const { return {right.data(), w, h}; }
};

TEST(DisparityRange, BracketsTheDisparityOfATexturedPair) {
  const RangePair p(150);
  const Rect roi{400, 80, 160, 120};
  RangeSearchParams rp;
  std::vector<std::byte> block(disparity_range_scratch_bytes(p.w, p.h, roi.w, roi.h, rp));
  Arena arena(block);
  auto r = find_disparity_range(p.l(), p.r(), roi, rp, MatchDpParams{}, arena);
  ASSERT_TRUE(r.ok()) << r.error().message;
  EXPECT_EQ(r->factor, 4);
  EXPECT_LE(r->min_px, 150);
  EXPECT_GE(r->max_px, 150);
  EXPECT_LE(r->max_px - r->min_px, 2 * rp.margin_px + 2 * r->factor);
  EXPECT_GT(r->coarse_matches, 500);
  EXPECT_EQ(arena.used(), 0u);
}

TEST(DisparityRange, TexturelessOrBadInputIsNamed) {
  std::vector<std::uint8_t> flat(640 * 300, 120);
  const ConstGray8View f(flat.data(), 640, 300);
  RangeSearchParams rp;
  std::vector<std::byte> block(disparity_range_scratch_bytes(640, 300, 160, 120, rp));
  Arena arena(block);
  auto r = find_disparity_range(f, f, Rect{400, 80, 160, 120}, rp, MatchDpParams{}, arena);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(std::string(r.error().message).find("disparity range"), std::string::npos);
  const RangePair p(100);
  r = find_disparity_range(p.l(), p.r(), Rect{600, 80, 160, 120}, rp, MatchDpParams{}, arena);
  EXPECT_EQ(r.code(), Errc::out_of_range);
  rp.search_max_px = rp.search_min_px;
  r = find_disparity_range(p.l(), p.r(), Rect{400, 80, 160, 120}, rp, MatchDpParams{}, arena);
  EXPECT_EQ(r.code(), Errc::invalid_argument);
}

}  // namespace
}  // namespace petra
