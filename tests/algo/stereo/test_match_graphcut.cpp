#include "algo/stereo/match_graphcut.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "tests/support/heap_counter.hpp"

namespace petra {
namespace {

// ---- An independent statement of the energy (docs/graphcut.md), written
// ---- from the definition, not from the matcher's code.
struct Problem {
  int width = 0, height = 0;
  std::vector<std::uint8_t> left, right, left_shadow, right_shadow;
  Rect roi;
  int disp_min = 0, disp_max = 0;
  int clip = 30, threshold = 8;
  std::int64_t k = 0, lambda1 = 0, lambda2 = 0;

  int at(const std::vector<std::uint8_t>& img, int x, int y) const {
    x = std::clamp(x, 0, width - 1);
    y = std::clamp(y, 0, height - 1);
    return img[y * width + x];
  }
  // Interval of a pixel and its half-way samples to the 4 neighbours.
  void interval(const std::vector<std::uint8_t>& img, int x, int y, double& lo, double& hi) const {
    const double i = at(img, x, y);
    lo = hi = i;
    const int dx[4] = {-1, 1, 0, 0}, dy[4] = {0, 0, -1, 1};
    for (int k2 = 0; k2 < 4; ++k2) {
      const double s = 0.5 * (i + at(img, x + dx[k2], y + dy[k2]));
      lo = std::min(lo, s);
      hi = std::max(hi, s);
    }
  }
  bool valid(int x, int y, int d) const {  // x, y in image coordinates
    const int xr = x - d;
    if (xr < 0 || xr >= width) return false;
    if (!left_shadow.empty() && left_shadow[y * width + x] != 0) return false;
    if (!right_shadow.empty() && right_shadow[y * width + xr] != 0) return false;
    return true;
  }
  // Data cost in units of 1/4 gray level squared.
  std::int64_t data(int x, int y, int d) const {
    double llo, lhi, rlo, rhi;
    interval(left, x, y, llo, lhi);
    interval(right, x - d, y, rlo, rhi);
    const double il = at(left, x, y), ir = at(right, x - d, y);
    const double d1 = std::max({0.0, il - rhi, rlo - il});
    const double d2 = std::max({0.0, ir - lhi, llo - ir});
    const double dist = std::min({d1, d2, static_cast<double>(clip)});
    return std::llround(4.0 * dist * dist);
  }
  std::int64_t potts(int x, int y, int nx, int ny, int d) const {
    const bool flat_left = std::abs(at(left, x, y) - at(left, nx, ny)) < threshold;
    const bool flat_right = std::abs(at(right, x - d, y) - at(right, nx - d, ny)) < threshold;
    return flat_left && flat_right ? lambda1 : lambda2;
  }
  // labels: per ROI pixel, -1 occluded or d - disp_min. Returns false when the
  // configuration breaks uniqueness or uses an invalid assignment.
  bool energy(const std::vector<int>& labels, std::int64_t& e) const {
    e = 0;
    for (int y = 0; y < roi.h; ++y) {
      std::vector<int> used(width, 0);
      for (int x = 0; x < roi.w; ++x) {
        const int l = labels[y * roi.w + x];
        if (l < 0) continue;
        const int gx = roi.x + x, gy = roi.y + y, d = disp_min + l;
        if (!valid(gx, gy, d)) return false;
        if (used[gx - d]++ != 0) return false;
        e += data(gx, gy, d) - k;
      }
    }
    // Every pair of neighbouring assignments with the same disparity.
    for (int y = 0; y < roi.h; ++y)
      for (int x = 0; x < roi.w; ++x)
        for (int dir = 0; dir < 2; ++dir) {
          const int nx = x + (dir == 0), ny = y + (dir == 1);
          if (nx >= roi.w || ny >= roi.h) continue;
          for (int d = disp_min; d <= disp_max; ++d) {
            const int gx = roi.x + x, gy = roi.y + y, gnx = roi.x + nx, gny = roi.y + ny;
            if (!valid(gx, gy, d) || !valid(gnx, gny, d)) continue;
            const bool a1 = labels[y * roi.w + x] == d - disp_min;
            const bool a2 = labels[ny * roi.w + nx] == d - disp_min;
            if (a1 != a2) e += potts(gx, gy, gnx, gny, d);
          }
        }
    return true;
  }
  // Minimum energy over every alpha-expansion of `labels` (brute force). With
  // a guide, only pixels whose guide is -1 or within `band` of alpha may
  // take alpha (a guided expansion).
  std::int64_t best_expansion(const std::vector<int>& labels, int alpha,
                              const std::vector<int>* guide = nullptr, int band = 0) const {
    std::vector<int> vars;  // pixel index; kept-old or added-alpha decided by bit
    std::vector<bool> is_old;
    for (int p = 0; p < roi.w * roi.h; ++p) {
      const int x = p % roi.w, y = p / roi.w;
      if (labels[p] >= 0 && labels[p] != alpha) {
        vars.push_back(p);
        is_old.push_back(true);
      }
      const bool in_band =
          guide == nullptr || (*guide)[p] < 0 || std::abs((*guide)[p] - alpha) <= band;
      if (labels[p] != alpha && in_band && valid(roi.x + x, roi.y + y, disp_min + alpha)) {
        vars.push_back(p);
        is_old.push_back(false);
      }
    }
    std::int64_t best = INT64_MAX;
    std::vector<int> trial(labels.size());
    for (std::uint32_t mask = 0; mask < (1u << vars.size()); ++mask) {
      trial = labels;
      for (std::size_t v = 0; v < vars.size(); ++v)
        if (is_old[v] && !((mask >> v) & 1u)) trial[vars[v]] = -1;
      bool clash = false;
      for (std::size_t v = 0; v < vars.size(); ++v) {
        if (is_old[v] || !((mask >> v) & 1u)) continue;
        if (trial[vars[v]] >= 0) clash = true;  // p would have two matches
        trial[vars[v]] = alpha;
      }
      std::int64_t e = 0;
      if (clash || !energy(trial, e)) continue;
      best = std::min(best, e);
    }
    return best;
  }
};

Problem random_problem(std::mt19937& rng, int w, int h, int disp_max, bool shadows) {
  Problem pr;
  pr.width = w;
  pr.height = h;
  pr.roi = {0, 0, w, h};
  pr.disp_min = 0;
  pr.disp_max = disp_max;
  std::uniform_int_distribution<int> gray(0, 60);  // a few levels: many ties and flat pairs
  for (int i = 0; i < w * h; ++i) {
    pr.left.push_back(static_cast<std::uint8_t>(gray(rng)));
    pr.right.push_back(static_cast<std::uint8_t>(gray(rng)));
  }
  if (shadows) {
    pr.left_shadow.assign(w * h, 0);
    pr.right_shadow.assign(w * h, 0);
    pr.left_shadow[rng() % (w * h)] = 255;
    pr.right_shadow[rng() % (w * h)] = 255;
  }
  return pr;
}

struct Trace {
  const Problem* problem = nullptr;
  std::vector<int> previous;  // labelling before the step
  std::vector<int> guide;     // the starting labelling (guided expansions' band)
  int band = 0;               // GraphCutParams::guided_radius
  int steps = 0, checked = 0;
  bool brute_force = false;
  std::int64_t last_energy = 0;
  std::vector<std::string> failures;
};

void check_step(void* context, const GraphCutStep& step) {
  auto& t = *static_cast<Trace*>(context);
  std::vector<int> now(step.labels.begin(), step.labels.end());
  std::int64_t e_now = 0;
  if (!t.problem->energy(now, e_now)) t.failures.push_back("labelling breaks uniqueness");
  if (e_now != step.energy_after) t.failures.push_back("reported energy differs from definition");
  if (step.cycle < 0) {  // the starting labelling
    t.guide = now;
    t.last_energy = step.energy_after;
    t.previous = now;
    return;
  }
  if (step.energy_after > step.energy_before) t.failures.push_back("energy increased");
  if (step.energy_before != t.last_energy) t.failures.push_back("energy trace has a gap");
  if (t.brute_force && !step.skipped) {
    const std::int64_t best = t.problem->best_expansion(
        t.previous, step.disparity - t.problem->disp_min, step.guided ? &t.guide : nullptr, t.band);
    std::int64_t e_before = 0;
    (void)t.problem->energy(t.previous, e_before);
    const std::int64_t expected = std::min(best, e_before);
    if (step.energy_after != expected) {
      t.failures.push_back("expansion on " + std::to_string(step.disparity) + " reached " +
                           std::to_string(step.energy_after) + ", optimum " +
                           std::to_string(expected));
    }
    ++t.checked;
  }
  t.last_energy = step.energy_after;
  t.previous = now;
  ++t.steps;
}

struct Run {
  GraphCutReport report;
  std::vector<std::int16_t> q4;
};

class GraphCutUnderTest {
 public:
  explicit GraphCutUnderTest(GraphCutBudget b)
      : block_(GraphCutMatcher::bytes_needed(b)), arena_(block_) {
    EXPECT_TRUE(m_.init(arena_, b).ok());
  }
  Result<Run> run(const Problem& pr, GraphCutParams params) {
    Run r;
    r.q4.assign(pr.roi.w * pr.roi.h, 0);
    DisparityMap out{ImageView<std::int16_t>(r.q4.data(), pr.roi.w, pr.roi.h), {}};
    StereoInput in;
    in.left = ConstGray8View(pr.left.data(), pr.width, pr.height);
    in.right = ConstGray8View(pr.right.data(), pr.width, pr.height);
    const Rect whole{0, 0, pr.width, pr.height};
    ShadowMask ls{ConstGray8View(pr.left_shadow.data(), pr.width, pr.height), whole};
    ShadowMask rs{ConstGray8View(pr.right_shadow.data(), pr.width, pr.height), whole};
    if (!pr.left_shadow.empty()) in.left_shadow = &ls;
    if (!pr.right_shadow.empty()) in.right_shadow = &rs;
    params.disp_min = pr.disp_min;
    params.disp_max = pr.disp_max;
    auto rep = m_.match(in, pr.roi, params, out);
    if (!rep) return rep.error();
    r.report = *rep;
    return r;
  }
  GraphCutMatcher& matcher() { return m_; }
  Arena& arena() { return arena_; }

 private:
  std::vector<std::byte> block_;
  Arena arena_;
  GraphCutMatcher m_;
};

std::vector<int> labels_of(const Run& r, int disp_min) {
  std::vector<int> l;
  for (std::int16_t q : r.q4)
    l.push_back(is_valid_disparity(q) ? q / kDisparityScale - disp_min : -1);
  return l;
}

// Every expansion reaches the exact optimum over its move space (brute force
// over all 2^n keep/add choices), with and without the node reduction, and
// the final labelling is a local minimum for every single expansion.
TEST(MatchGraphCut, EachExpansionIsOptimalAndTheResultIsALocalMinimum) {
  std::mt19937 rng(2024);
  GraphCutUnderTest m({4, 2, 4});
  int checked = 0;
  for (int round = 0; round < 16; ++round) {
    const int w = 3 + round % 2, h = 2, disp_max = 1 + round % 3;
    Problem pr = random_problem(rng, w, h, disp_max, round % 3 == 2);
    GraphCutParams params;
    params.max_cycles = 8;
    params.prune = round % 2 == 0;
    params.start = static_cast<GraphCutStart>(round % 3);
    // The last rounds start from a given map: random disparities, some
    // between pixels, invalid or out of range, some claiming one right pixel.
    std::vector<std::int16_t> start(static_cast<std::size_t>(w * h));
    if (round >= 12) {
      std::uniform_int_distribution<int> q4(-20, 16 * disp_max + 20);
      for (auto& v : start)
        v = rng() % 5 == 0 ? kInvalidDisparity : static_cast<std::int16_t>(q4(rng));
      params.start = GraphCutStart::given;
      params.start_map = ConstDisparityMap(ImageView<const std::int16_t>(start.data(), w, h), {});
    }
    params.guided_cycles = round % 4 < 2 ? 1 : 2;
    params.guided_radius = (round / 2) % 2;
    params.seed = static_cast<std::uint32_t>(round + 1);
    // Small weights relative to the data so moves are not trivial.
    params.occlusion_k = 400 + 100 * (round % 4);
    params.lambda1 = 60 + 40 * (round % 3);
    params.lambda2 = 20;
    pr.k = params.occlusion_k;
    pr.lambda1 = params.lambda1;
    pr.lambda2 = params.lambda2;
    Trace trace;
    trace.problem = &pr;
    trace.brute_force = true;
    trace.band = params.guided_radius;
    trace.previous.assign(w * h, -1);
    params.observer = {check_step, &trace};
    auto run = m.run(pr, params);
    ASSERT_TRUE(run.ok()) << run.error().message;
    for (const auto& f : trace.failures) ADD_FAILURE() << "round " << round << ": " << f;
    ASSERT_TRUE(run->report.converged) << "round " << round;
    const std::vector<int> final_labels = labels_of(*run, pr.disp_min);
    std::int64_t e = 0;
    ASSERT_TRUE(pr.energy(final_labels, e));
    EXPECT_EQ(e, run->report.energy);
    for (int alpha = 0; alpha <= disp_max; ++alpha) {
      EXPECT_GE(pr.best_expansion(final_labels, alpha), e)
          << "round " << round << " alpha " << alpha;
    }
    checked += trace.checked;
  }
  EXPECT_GT(checked, 50);
}

// A textured plane at disparity 2 with a nearer square at 7 in front of it.
struct Scene {
  Problem pr;
  std::vector<int> truth;  // per pixel: disparity, or -1 where occluded
};

Scene square_scene(int w, int h, int d_bg, int d_fg, Rect square, Rect roi, int disp_min,
                   int disp_max, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> tex(0, 255), noise(-2, 2);
  std::vector<int> bg(w * h), fg(w * h);
  for (auto& v : bg) v = tex(rng);
  for (auto& v : fg) v = tex(rng);
  auto clamp_px = [](int v) { return static_cast<std::uint8_t>(std::clamp(v, 0, 255)); };
  Scene s;
  s.pr.width = w;
  s.pr.height = h;
  s.pr.roi = roi;
  s.pr.disp_min = disp_min;
  s.pr.disp_max = disp_max;
  s.pr.left.resize(w * h);
  s.pr.right.resize(w * h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const bool in_fg = square.contains(x, y);
      s.pr.left[y * w + x] = clamp_px(in_fg ? fg[y * w + x] : bg[y * w + x]);
      const bool right_fg = square.contains(x + d_fg, y);
      const int src = right_fg ? fg[y * w + x + d_fg] : (x + d_bg < w ? bg[y * w + x + d_bg] : 128);
      s.pr.right[y * w + x] = clamp_px(src + noise(rng));
    }
  for (int y = roi.y; y < roi.y + roi.h; ++y)
    for (int x = roi.x; x < roi.x + roi.w; ++x) {
      int t = square.contains(x, y) ? d_fg : d_bg;
      if (x - t < 0) t = -1;                                         // leaves the image
      if (t == d_bg && square.contains(x - d_bg + d_fg, y)) t = -1;  // hidden by the square
      s.truth.push_back(t);
    }
  return s;
}

TEST(MatchGraphCut, RecoversAPlaneAndASquareWithTheirOcclusion) {
  const Scene s = square_scene(64, 40, 2, 7, {28, 12, 20, 16}, {0, 0, 64, 40}, 0, 9, 5);
  GraphCutUnderTest m({64, 40, 10});
  GraphCutParams params;
  params.max_cycles = 4;  // to convergence
  auto run = m.run(s.pr, params);
  ASSERT_TRUE(run.ok()) << run.error().message;
  int visible = 0, right = 0, occluded = 0, marked = 0;
  for (std::size_t p = 0; p < s.truth.size(); ++p) {
    const std::int16_t q = run->q4[p];
    if (s.truth[p] >= 0) {
      ++visible;
      if (is_valid_disparity(q) && q == s.truth[p] * kDisparityScale) ++right;
    } else {
      ++occluded;
      if (!is_valid_disparity(q)) ++marked;
    }
  }
  // Random texture is easy: nearly every visible pixel is exact, and most of
  // the occluded strip beside the square is detected as such.
  EXPECT_GE(right, visible * 97 / 100) << right << " of " << visible;
  EXPECT_GE(marked, occluded * 80 / 100) << marked << " of " << occluded;
  EXPECT_TRUE(run->report.converged);
  EXPECT_EQ(run->report.start, GraphCutStart::dp);
  EXPECT_EQ(run->report.guided_cycles, 1);
  EXPECT_GT(run->report.occlusion_k, 0);
  EXPECT_EQ(run->report.lambda1, 3 * run->report.lambda2);
  // Energy per cycle never increases.
  for (std::size_t c = 1; c < run->report.cycle_energy.size(); ++c)
    EXPECT_LE(run->report.cycle_energy[c], run->report.cycle_energy[c - 1]);
}

// The DP start needs edges; where it finds nothing (a flat ROI) the matcher
// starts from block matching instead, and still runs.
TEST(MatchGraphCut, DpStartFallsBackToBlockMatchingWhenTheDpFindsNothing) {
  Scene s = square_scene(40, 24, 2, 6, {16, 6, 12, 10}, {0, 0, 40, 24}, 0, 8, 3);
  std::fill(s.pr.left.begin(), s.pr.left.end(), std::uint8_t{90});
  std::fill(s.pr.right.begin(), s.pr.right.end(), std::uint8_t{90});
  GraphCutUnderTest m({40, 24, 9});
  auto run = m.run(s.pr, GraphCutParams{});
  ASSERT_TRUE(run.ok()) << run.error().message;
  EXPECT_EQ(run->report.start, GraphCutStart::block_matching);
  // On the textured scene the DP start is taken.
  const Scene textured = square_scene(40, 24, 2, 6, {16, 6, 12, 10}, {0, 0, 40, 24}, 0, 8, 3);
  auto run2 = m.run(textured.pr, GraphCutParams{});
  ASSERT_TRUE(run2.ok()) << run2.error().message;
  EXPECT_EQ(run2->report.start, GraphCutStart::dp);
}

// Given the DP's own map, the matcher starts where the DP start does and
// ends with the same labels and energy.
TEST(MatchGraphCut, GivenStartFromTheDpMapEqualsTheDpStart) {
  const Scene s = square_scene(64, 40, 2, 7, {28, 12, 20, 16}, {4, 2, 56, 36}, 0, 9, 11);
  const Problem& pr = s.pr;
  std::vector<std::int16_t> dp_q4(static_cast<std::size_t>(pr.roi.w * pr.roi.h));
  DisparityMap dp_map{ImageView<std::int16_t>(dp_q4.data(), pr.roi.w, pr.roi.h), {}};
  const MatchBudget budget{64, 40, 10};
  std::vector<std::byte> block(match_dp_scratch_bytes(budget));
  Arena arena(block);
  MatchDpParams dp;
  dp.disp_min = pr.disp_min;
  dp.disp_max = pr.disp_max;
  const StereoInput in{ConstGray8View(pr.left.data(), pr.width, pr.height),
                       ConstGray8View(pr.right.data(), pr.width, pr.height)};
  ASSERT_TRUE(match_dp(in, pr.roi, dp, budget, arena, dp_map).ok());
  GraphCutUnderTest m({64, 40, 10});
  auto from_dp = m.run(pr, GraphCutParams{});
  ASSERT_TRUE(from_dp.ok()) << from_dp.error().message;
  GraphCutParams given;
  given.start = GraphCutStart::given;
  given.start_map = dp_map;
  auto from_map = m.run(pr, given);
  ASSERT_TRUE(from_map.ok()) << from_map.error().message;
  EXPECT_EQ(from_dp->report.start, GraphCutStart::dp);
  EXPECT_EQ(from_map->report.start, GraphCutStart::given);
  EXPECT_EQ(from_map->report.energy_start, from_dp->report.energy_start);
  EXPECT_EQ(from_map->report.energy, from_dp->report.energy);
  EXPECT_EQ(from_map->q4, from_dp->q4);
  // Another map gives another start.
  std::fill(dp_q4.begin(), dp_q4.end(), std::int16_t{2 * kDisparityScale});
  auto flat = m.run(pr, given);
  ASSERT_TRUE(flat.ok()) << flat.error().message;
  EXPECT_NE(flat->report.energy_start, from_dp->report.energy_start);
}

TEST(MatchGraphCut, RoiAndNegativeDisparitiesUseImageCoordinates) {
  // Same scene seen through an ROI, disparities searched from -3: the result
  // inside the ROI is the scene's disparity in rectified image coordinates.
  const Scene s = square_scene(80, 48, 2, 7, {40, 16, 16, 16}, {30, 10, 36, 30}, -3, 9, 11);
  GraphCutUnderTest m({40, 32, 16});
  auto run = m.run(s.pr, GraphCutParams{});
  ASSERT_TRUE(run.ok()) << run.error().message;
  int visible = 0, right = 0;
  for (std::size_t p = 0; p < s.truth.size(); ++p) {
    if (s.truth[p] < 0) continue;
    ++visible;
    if (run->q4[p] == s.truth[p] * kDisparityScale) ++right;
  }
  EXPECT_GE(right, visible * 95 / 100) << right << " of " << visible;
}

TEST(MatchGraphCut, EnergyNeverIncreasesAndMatchesItsDefinition) {
  const Scene s = square_scene(40, 24, 2, 6, {16, 6, 12, 10}, {0, 0, 40, 24}, 0, 8, 3);
  GraphCutUnderTest m({40, 24, 9});
  GraphCutParams params;
  params.max_cycles = 6;
  // First run to learn the automatic parameters, then trace with them.
  auto first = m.run(s.pr, params);
  ASSERT_TRUE(first.ok());
  Problem pr = s.pr;
  pr.k = first->report.occlusion_k;
  pr.lambda1 = first->report.lambda1;
  pr.lambda2 = first->report.lambda2;
  Trace trace;
  trace.problem = &pr;
  trace.previous.assign(pr.roi.w * pr.roi.h, -1);
  params.observer = {check_step, &trace};
  auto run = m.run(pr, params);
  ASSERT_TRUE(run.ok());
  for (const auto& f : trace.failures) ADD_FAILURE() << f;
  EXPECT_EQ(trace.steps, (run->report.guided_cycles + run->report.cycles) * 9);
  EXPECT_EQ(trace.failures.size(), 0u);
  EXPECT_EQ(run->report.energy, first->report.energy);  // deterministic
  EXPECT_LT(run->report.energy, 0);
}

TEST(MatchGraphCut, PruningKeepsTheSameResult) {
  const Scene s = square_scene(48, 32, 1, 5, {20, 10, 14, 12}, {0, 0, 48, 32}, 0, 7, 8);
  GraphCutUnderTest m({48, 32, 8});
  GraphCutParams params;
  params.random_order = false;
  auto pruned = m.run(s.pr, params);
  params.prune = false;
  auto full = m.run(s.pr, params);
  ASSERT_TRUE(pruned.ok() && full.ok());
  // Each expansion reaches the same minimum; ties aside the paths coincide.
  EXPECT_EQ(pruned->report.energy, full->report.energy);
  EXPECT_LT(pruned->report.graph_nodes, full->report.graph_nodes);
}

TEST(MatchGraphCut, ShadowPixelsGetNoDisparityAndNoMatchLandsInShadow) {
  Scene s = square_scene(48, 32, 2, 6, {20, 8, 12, 12}, {0, 0, 48, 32}, 0, 8, 21);
  s.pr.left_shadow.assign(48 * 32, 0);
  s.pr.right_shadow.assign(48 * 32, 0);
  for (int y = 20; y < 28; ++y)
    for (int x = 5; x < 15; ++x) s.pr.left_shadow[y * 48 + x] = 1;
  for (int y = 2; y < 10; ++y)
    for (int x = 30; x < 40; ++x) s.pr.right_shadow[y * 48 + x] = 1;
  GraphCutUnderTest m({48, 32, 9});
  auto run = m.run(s.pr, GraphCutParams{});
  ASSERT_TRUE(run.ok());
  long shadow = 0;
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 48; ++x) {
      const std::int16_t q = run->q4[y * 48 + x];
      if (s.pr.left_shadow[y * 48 + x]) {
        ++shadow;
        EXPECT_FALSE(is_valid_disparity(q));
      } else if (is_valid_disparity(q)) {
        EXPECT_EQ(s.pr.right_shadow[y * 48 + x - q / kDisparityScale], 0) << x << "," << y;
      }
    }
  EXPECT_EQ(run->report.shadow_pixels, shadow);
  EXPECT_EQ(run->report.matched_pixels + run->report.occluded_pixels + shadow, 48 * 32);
}

TEST(MatchGraphCut, SeededOrderIsDeterministic) {
  const Scene s = square_scene(40, 24, 2, 6, {16, 6, 12, 10}, {0, 0, 40, 24}, 0, 8, 4);
  GraphCutUnderTest m({40, 24, 9});
  GraphCutParams params;
  params.seed = 77;
  auto a = m.run(s.pr, params);
  auto b = m.run(s.pr, params);
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_EQ(a->q4, b->q4);
  EXPECT_EQ(a->report.energy, b->report.energy);
}

TEST(MatchGraphCut, RepeatedCallsAllocateNothing) {
  const Scene s = square_scene(40, 24, 2, 6, {16, 6, 12, 10}, {0, 0, 40, 24}, 0, 8, 4);
  GraphCutUnderTest m({40, 24, 9});
  std::vector<std::int16_t> q4(40 * 24);
  DisparityMap out{ImageView<std::int16_t>(q4.data(), 40, 24), {}};
  StereoInput in{ConstGray8View(s.pr.left.data(), 40, 24),
                 ConstGray8View(s.pr.right.data(), 40, 24)};
  GraphCutParams params;
  params.disp_max = 8;
  test::HeapScope scope;
  for (int k = 0; k < 3; ++k) {
    params.seed = static_cast<std::uint32_t>(k + 1);
    auto rep = m.matcher().match(in, {0, 0, 40, 24}, params, out);
    EXPECT_TRUE(rep.ok());
  }
  EXPECT_EQ(scope.allocations(), 0u);
}

// A cancel hook that answers "stop" from its n-th question on.
struct CancelAfter {
  int questions = 0;
  int stop_at = 0;
  static bool ask(void* context) {
    auto& c = *static_cast<CancelAfter*>(context);
    return ++c.questions >= c.stop_at;
  }
};

TEST(MatchGraphCut, CancelStopsBetweenExpansionsAndLeavesTheOutputAlone) {
  const Scene s = square_scene(40, 24, 2, 6, {16, 6, 12, 10}, {0, 0, 40, 24}, 0, 8, 4);
  GraphCutUnderTest m({40, 24, 9});
  std::vector<std::int16_t> q4(40 * 24, 123);
  DisparityMap out{ImageView<std::int16_t>(q4.data(), 40, 24), {}};
  StereoInput in{ConstGray8View(s.pr.left.data(), 40, 24),
                 ConstGray8View(s.pr.right.data(), 40, 24)};
  GraphCutParams params;
  params.disp_max = 8;
  params.random_order = false;
  CancelAfter asked{0, 4};
  StepClock clock;
  clock.cancel_requested = CancelAfter::ask;
  clock.context = &asked;
  params.cancel = &clock;
  auto stopped = m.matcher().match(in, {0, 0, 40, 24}, params, out);
  ASSERT_FALSE(stopped.ok());
  EXPECT_EQ(stopped.error().code, Errc::cancelled);
  EXPECT_EQ(asked.questions, 4);  // asked once per expansion, stopped at once
  EXPECT_TRUE(std::all_of(q4.begin(), q4.end(), [](std::int16_t v) { return v == 123; }));
  // Never asked to stop: the hook is polled before every expansion and the
  // result is that of a run without it.
  CancelAfter never{0, 1 << 30};
  clock.context = &never;
  auto full = m.matcher().match(in, {0, 0, 40, 24}, params, out);
  ASSERT_TRUE(full.ok());
  EXPECT_EQ(never.questions, full->expansions + full->expansions_skipped);
  const std::vector<std::int16_t> with_hook = q4;
  params.cancel = nullptr;
  ASSERT_TRUE(m.matcher().match(in, {0, 0, 40, 24}, params, out).ok());
  EXPECT_EQ(q4, with_hook);
}

TEST(MatchGraphCut, BadInputIsRefusedWithTheFieldNamed) {
  const Scene s = square_scene(40, 24, 2, 6, {16, 6, 12, 10}, {0, 0, 40, 24}, 0, 8, 4);
  GraphCutUnderTest m({40, 24, 9});
  std::vector<std::int16_t> q4(40 * 24);
  DisparityMap out{ImageView<std::int16_t>(q4.data(), 40, 24), {}};
  const StereoInput in{ConstGray8View(s.pr.left.data(), 40, 24),
                       ConstGray8View(s.pr.right.data(), 40, 24)};
  StereoInput small = in;
  small.right = ConstGray8View(s.pr.right.data(), 30, 24);
  GraphCutParams p;
  p.disp_max = 8;
  auto expect_error = [&](Result<GraphCutReport> res, Errc code, const char* word) {
    ASSERT_FALSE(res.ok());
    EXPECT_EQ(res.code(), code);
    EXPECT_NE(std::string(res.error().message).find(word), std::string::npos)
        << res.error().message;
  };
  GraphCutMatcher& gc = m.matcher();
  expect_error(gc.match(small, {0, 0, 40, 24}, p, out), Errc::invalid_argument, "right image");
  expect_error(gc.match(in, {10, 0, 40, 24}, p, out), Errc::out_of_range, "roi");
  GraphCutParams q = p;
  q.disp_min = 5;
  q.disp_max = 2;
  expect_error(gc.match(in, {0, 0, 40, 24}, q, out), Errc::invalid_argument, "disparity range");
  q = p;
  q.disp_max = 20;
  expect_error(gc.match(in, {0, 0, 40, 24}, q, out), Errc::capacity_exceeded, "budget");
  q = p;
  q.max_cycles = 0;
  expect_error(gc.match(in, {0, 0, 40, 24}, q, out), Errc::out_of_range, "max_cycles");
  q = p;
  q.occlusion_k = -5;
  expect_error(gc.match(in, {0, 0, 40, 24}, q, out), Errc::out_of_range, "occlusion_k");
  q = p;
  q.lambda1 = -3;
  expect_error(gc.match(in, {0, 0, 40, 24}, q, out), Errc::out_of_range, "lambda1");
  q = p;
  q.data_clip = 200;
  expect_error(gc.match(in, {0, 0, 40, 24}, q, out), Errc::out_of_range, "data_clip");
  q = p;
  q.guided_cycles = -1;
  expect_error(gc.match(in, {0, 0, 40, 24}, q, out), Errc::out_of_range, "guided_cycles");
  q = p;
  q.guided_radius = -1;
  expect_error(gc.match(in, {0, 0, 40, 24}, q, out), Errc::out_of_range, "guided_radius");
  q = p;
  q.start = static_cast<GraphCutStart>(7);
  expect_error(gc.match(in, {0, 0, 40, 24}, q, out), Errc::invalid_argument, "start");
  q = p;
  q.start = GraphCutStart::given;  // without its map
  expect_error(gc.match(in, {0, 0, 40, 24}, q, out), Errc::invalid_argument, "start_map");
  std::vector<std::int16_t> small_start(39 * 24, 0);
  q.start_map = ConstDisparityMap(ImageView<const std::int16_t>(small_start.data(), 39, 24), {});
  expect_error(gc.match(in, {0, 0, 40, 24}, q, out), Errc::invalid_argument, "start_map 39x24");
  q = p;
  q.dp_start.p1 = -1;  // the DP start's own parameters are checked by match_dp
  expect_error(gc.match(in, {0, 0, 40, 24}, q, out), Errc::invalid_argument, "match_dp");
  std::vector<std::int16_t> small_out(10);
  DisparityMap bad{ImageView<std::int16_t>(small_out.data(), 5, 2), {}};
  expect_error(gc.match(in, {0, 0, 40, 24}, p, bad), Errc::invalid_argument, "output");
  std::vector<std::uint8_t> mask(10 * 10, 0);
  const ShadowMask outside{ConstGray8View(mask.data(), 10, 10), {35, 0, 10, 10}};
  StereoInput masked = in;
  masked.left_shadow = &outside;
  expect_error(gc.match(masked, {0, 0, 40, 24}, p, out), Errc::invalid_argument, "shadow mask");
  // Nothing to match: the disparities all point outside the image.
  q = p;
  q.disp_min = 45;
  q.disp_max = 50;
  expect_error(gc.match(in, {0, 0, 40, 24}, q, out), Errc::degenerate, "valid disparities");
  GraphCutMatcher uninitialised;
  expect_error(uninitialised.match(in, {0, 0, 40, 24}, p, out), Errc::not_ready, "init");
}

TEST(MatchGraphCut, FlightBudgetFitsItsStatedMemory) {
  const GraphCutBudget flight;  // 320 x 320 ROI, 128 disparities
  const std::size_t bytes = GraphCutMatcher::bytes_needed(flight);
  EXPECT_LT(bytes, std::size_t{23'700'000});  // docs/graphcut.md: 23.7 MB
  std::vector<std::byte> block(bytes);
  Arena arena(block);
  GraphCutMatcher m;
  ASSERT_TRUE(m.init(arena, flight).ok());
  EXPECT_LE(arena.used(), bytes);
  std::vector<std::byte> short_block(bytes / 2);
  Arena short_arena(short_block);
  GraphCutMatcher m2;
  EXPECT_EQ(m2.init(short_arena, flight).code(), Errc::capacity_exceeded);
}

}  // namespace
}  // namespace petra
