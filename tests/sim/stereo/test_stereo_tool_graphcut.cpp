// `petra stereo --method gc` end to end through its library function: the
// Middlebury pairs (whole images, budget sized for them), ROI and fill
// handling, and simulated rock scenes (sim/scene) rectified with their
// calib.json and scored against the rendered disparity truth.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "sim/eval/middlebury.hpp"
#include "sim/io/image_io.hpp"
#include "sim/scene/scene_render.hpp"
#include "sim/scene/scene_set.hpp"
#include "sim/stereo/stereo_tool.hpp"

namespace petra::stereo {
namespace {

const std::string kRoot = eval::default_data_root(PETRA_SOURCE_DIR);
const std::string kGcTmp = ::testing::TempDir();

StereoToolOptions middlebury(const char* name) {
  const eval::MiddleburyScene* s = eval::find_middlebury_scene(name);
  StereoToolOptions o;
  o.method = "gc";
  o.left = kRoot + "/" + s->dir + "/" + s->left;
  o.right = kRoot + "/" + s->dir + "/" + s->right;
  o.disp_min = 0;
  o.disp_max = s->disp_max;
  o.out = kGcTmp + "petra_stereo_gc_" + name + ".pfm";
  return o;
}

TEST(StereoToolGraphCut, FilledTsukubaScoresLikeTheMatcher) {
  StereoToolOptions o = middlebury("tsukuba");
  o.fill = true;
  auto r = run_stereo_tool(o);
  ASSERT_TRUE(r.ok()) << r.error().message;
  EXPECT_EQ(r->graph.guided_cycles, 1);
  EXPECT_EQ(r->graph.cycles, 1);
  EXPECT_EQ(r->graph.start, GraphCutStart::dp);
  auto pfm = io::read_pfm(o.out);
  ASSERT_TRUE(pfm.ok());
  auto data = eval::load_middlebury(*eval::find_middlebury_scene("tsukuba"), kRoot);
  ASSERT_TRUE(data.ok());
  auto score = eval::score_middlebury(pfm->view(), *data);
  ASSERT_TRUE(score.ok());
  // Filled by the tool: strict equals filled, at the published KZ figure.
  EXPECT_NEAR(score->strict.all, score->filled.all, 1e-9);
  EXPECT_LE(score->filled.all, 2.01);
}

TEST(StereoToolGraphCut, RoiOutputIsInfOutsideAndOccludedInsideUnlessFilled) {
  StereoToolOptions o = middlebury("tsukuba");
  o.roi = "100,80,120,90";
  auto r = run_stereo_tool(o);
  ASSERT_TRUE(r.ok()) << r.error().message;
  auto pfm = io::read_pfm(o.out);
  ASSERT_TRUE(pfm.ok());
  long finite = 0, holes = 0;
  for (int y = 0; y < 288; ++y)
    for (int x = 0; x < 384; ++x) {
      const float v = pfm->data[static_cast<std::size_t>(y) * 384 + x];
      const bool inside = x >= 100 && x < 220 && y >= 80 && y < 170;
      if (!inside) {
        EXPECT_TRUE(std::isinf(v));
      } else if (std::isfinite(v)) {
        ++finite;
        EXPECT_EQ(v, std::round(v));  // integer disparities
      } else {
        ++holes;
      }
    }
  EXPECT_EQ(finite, r->matched);
  EXPECT_EQ(holes, r->graph.occluded_pixels);
  EXPECT_GT(holes, 0);  // occlusions at the object edges are explicit
  o.fill = true;
  ASSERT_TRUE(run_stereo_tool(o).ok());
  auto filled = io::read_pfm(o.out);
  ASSERT_TRUE(filled.ok());
  for (int y = 80; y < 170; ++y)
    for (int x = 100; x < 220; ++x)
      EXPECT_TRUE(std::isfinite(filled->data[static_cast<std::size_t>(y) * 384 + x]));
}

// The largest pair of the shared data (Aloe, 641x555, 112 disparities): the
// tool sizes the budget for the whole image and it runs. The accuracy of all
// eight pairs is in the benchmark (docs/performance.md).
TEST(StereoToolGraphCut, LargestMiddleburyPairRuns) {
  StereoToolOptions o = middlebury("Aloe");
  auto r = run_stereo_tool(o);
  ASSERT_TRUE(r.ok()) << r.error().message;
  EXPECT_GT(r->matched, 641L * 555 * 8 / 10);
}

TEST(StereoToolGraphCut, BadInputIsRefused) {
  StereoToolOptions o = middlebury("tsukuba");
  o.disp_min = 10;
  o.disp_max = 2;
  auto r = run_stereo_tool(o);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(std::string(r.error().message).find("empty range"), std::string::npos);
  o = middlebury("tsukuba");
  o.disp_min = 400;
  o.disp_max = 420;
  r = run_stereo_tool(o);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(std::string(r.error().message).find("valid disparities"), std::string::npos);
}

// Simulated rock scenes: the pair is rectified with the scene's calib.json,
// the ROI is the operator's (truth.json), the range the truth's with 2 px of
// margin; scored over the ROI pixels with a valid truth disparity, missing
// disparities counted bad. Thresholds: bad-1 < 18% and bad-2 < 6%.
// Why: at this range (0.5-0.9 m, 150 mm baseline, 1024x768) the ground and the
// rock faces are steep slants, the disparity changing by 0.2-0.3 px per row,
// and the model has integer disparities with a Potts prior: it tracks such a
// surface with constant-disparity bands whose steps come a row or two late
// where the data is weak. The error is then zero-mean with a spread of about
// 0.65 px, so a tenth of the pixels sit just past the 1 px of bad-1 (measured
// 9.4-15.4% on these scenes, nearly all with |error| in (1, 2]); uniqueness also
// leaves a few pixels of faces foreshortened in the right view unmatched
// (2-3%). Gross errors (bad-2) stay rare: 2.3-4.6%. A matcher that failed on
// the rock or the ground, or a 1 px shift, would exceed both bounds by far;
// the pipeline's mean filter (docs/method.md 3c) smooths the steps before
// triangulation.
TEST(StereoToolGraphCut, SimulatedScenesAgreeWithTheRenderedTruth) {
  const auto set = sim::standard_scene_set();
  for (int k : {0, 5, 11}) {
    auto products = sim::render_scene(set[k]);
    ASSERT_TRUE(products.ok()) << products.error().message;
    const std::string dir = kGcTmp + "petra_gc_scene_" + std::to_string(k);
    ASSERT_TRUE(sim::write_scene(*products, dir).ok());
    const sim::SceneTruth& t = products->truth;
    StereoToolOptions o;
    o.method = "gc";
    o.left = dir + "/left.png";
    o.right = dir + "/right.png";
    o.calib = dir + "/calib.json";
    o.roi = std::to_string(t.roi.x) + "," + std::to_string(t.roi.y) + "," +
            std::to_string(t.roi.w) + "," + std::to_string(t.roi.h);
    o.disp_min = static_cast<int>(std::floor(t.disparity_min)) - 2;
    o.disp_max = static_cast<int>(std::ceil(t.disparity_max)) + 2;
    o.out = dir + "/gc.pfm";
    auto r = run_stereo_tool(o);
    ASSERT_TRUE(r.ok()) << r.error().message;
    auto disp = io::read_pfm(o.out);
    ASSERT_TRUE(disp.ok());
    const io::FloatImage& truth = products->rectified.disparity;
    ASSERT_EQ(disp->width, truth.width);
    long valid = 0, bad1 = 0, bad2 = 0;
    for (int y = r->roi.y; y < r->roi.y + r->roi.h; ++y)
      for (int x = r->roi.x; x < r->roi.x + r->roi.w; ++x) {
        const std::size_t i = static_cast<std::size_t>(y) * truth.width + x;
        if (!std::isfinite(truth.data[i])) continue;
        ++valid;
        const float d = disp->data[i];
        const float e = std::isfinite(d) ? std::fabs(d - truth.data[i]) : 1e9f;
        bad1 += e > 1.0f ? 1 : 0;
        bad2 += e > 2.0f ? 1 : 0;
      }
    ASSERT_GT(valid, 10000) << "scene " << k;
    const double pct1 = 100.0 * static_cast<double>(bad1) / static_cast<double>(valid);
    const double pct2 = 100.0 * static_cast<double>(bad2) / static_cast<double>(valid);
    std::printf(
        "scene %d (seed %llu): ROI %dx%d, disparities %d..%d: bad-1 %.2f%%, bad-2 %.2f%% "
        "of %ld px\n",
        k, static_cast<unsigned long long>(set[k].seed), r->roi.w, r->roi.h, o.disp_min, o.disp_max,
        pct1, pct2, valid);
    EXPECT_LT(pct1, 18.0) << "scene " << k;
    EXPECT_LT(pct2, 6.0) << "scene " << k;
  }
}

}  // namespace
}  // namespace petra::stereo
