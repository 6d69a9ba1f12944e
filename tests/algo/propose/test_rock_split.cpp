// The saddle split of detection's rock points (algo/propose/rock_split) on
// small hand-made height grids: two maxima over a deep saddle are two parts,
// over a shallow one a single part; a lone spike (fewer than min_pixels
// points) joins the rock it stands on; ground points belong to no part.
#include <gtest/gtest.h>

#include <cstddef>
#include <cstdint>
#include <set>
#include <vector>

#include "algo/propose/rock_split.hpp"

namespace petra {
namespace {

// A w x h grid with a point on every pixel; heights by `h(x, y)`, points at
// or below 0 are ground.
struct HeightGrid {
  int w, h;
  std::vector<std::int32_t> index;
  std::vector<PixelPos> pixels;
  std::vector<float> height;
  std::vector<PointClass> labels;
  std::vector<std::int32_t> part;
  template <class F>
  HeightGrid(int w_, int h_, F f) : w(w_), h(h_) {
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        index.push_back(static_cast<std::int32_t>(pixels.size()));
        pixels.push_back({static_cast<std::int16_t>(x), static_cast<std::int16_t>(y)});
        height.push_back(static_cast<float>(f(x, y)));
        labels.push_back(height.back() > 0 ? PointClass::rock : PointClass::ground);
      }
    part.assign(pixels.size(), 0);
  }
  std::set<std::int32_t> parts(const SplitParams& p) {
    std::vector<std::int32_t> order(pixels.size()), sizes(pixels.size());
    const Status s = split_at_saddles({w, h, index, pixels}, height, labels, p, part, order, sizes);
    EXPECT_TRUE(s.ok()) << s.error().message;
    std::set<std::int32_t> out;
    for (std::size_t i = 0; i < part.size(); ++i)
      if (labels[i] == PointClass::rock) out.insert(part[i]);
    return out;
  }
  std::int32_t at(int x, int y) const { return part[static_cast<std::size_t>(y * w + x)]; }
};

// Two tents along x (peaks at x = 6 and 18) meeting at x = 12 at `saddle` mm.
HeightGrid two_tents(double peak_a, double peak_b, double saddle) {
  return HeightGrid(25, 7, [=](int x, int) {
    if (x <= 12) return saddle + (peak_a - saddle) * (1.0 - std::abs(x - 6) / 6.0);
    return saddle + (peak_b - saddle) * (1.0 - std::abs(x - 18) / 6.0);
  });
}

TEST(RockSplit, TwoMaximaOverADeepSaddleAreTwoParts) {
  HeightGrid g = two_tents(55, 50, 30);  // both peaks 20+ mm above the saddle
  EXPECT_EQ(g.parts({12.0, 12}).size(), 2u);
  EXPECT_NE(g.at(6, 3), g.at(18, 3));
  EXPECT_EQ(g.at(2, 0), g.at(6, 3));
  EXPECT_EQ(g.at(22, 6), g.at(18, 3));
}

TEST(RockSplit, AShallowSaddleIsOneRock) {
  HeightGrid g = two_tents(55, 40, 30);  // the lower peak 10 mm above the saddle
  EXPECT_EQ(g.parts({12.0, 12}).size(), 1u);
  EXPECT_EQ(g.parts({8.0, 12}).size(), 2u);  // ... two parts when 8 mm suffices
}

TEST(RockSplit, ALoneSpikeJoinsItsRock) {
  // A 40 mm plateau with one mismatched point 200 mm high: 1 point, not 12.
  HeightGrid g(15, 7, [](int x, int y) { return x == 7 && y == 3 ? 200.0 : 40.0; });
  EXPECT_EQ(g.parts({12.0, 12}).size(), 1u);
}

TEST(RockSplit, GroundBelongsToNoPartAndGapsSeparate) {
  // Two plateaus with a column of ground between them: apart without a saddle.
  HeightGrid g(15, 5, [](int x, int) { return x == 7 ? 0.0 : 30.0; });
  EXPECT_EQ(g.parts({12.0, 12}).size(), 2u);
  EXPECT_EQ(g.at(7, 2), kNoSplitPart);
}

}  // namespace
}  // namespace petra
