// `petra sim scene` outputs: the same seed and options give identical bytes,
// other seeds give other scenes, and every file reads back as documented.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "algo/calib_json.hpp"
#include "sim/scene/scene_render.hpp"
#include "sim/scene/scene_set.hpp"
#include "sim/score/truth_file.hpp"

namespace petra::sim {
namespace {

namespace fs = std::filesystem;

const char* const kFiles[] = {"left.pgm",        "right.pgm",           "left.png",
                              "right.png",       "calib.json",          "truth.json",
                              "disparity_truth.pfm", "shadow_truth.pgm", "shadow_truth_right.pgm",
                              "shadow_truth_rectified.pgm"};

std::string bytes(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}

fs::path temp_dir(const char* name) {
  const fs::path d = fs::temp_directory_path() / (std::string("petra_scene_") + name);
  fs::remove_all(d);
  return d;
}

// One scene rendered once for the whole suite (rendering is the slow part).
const SceneProducts& products() {
  static const SceneProducts p = [] {
    auto r = render_scene(standard_scene_set()[5]);
    EXPECT_TRUE(r.ok()) << r.error().message;
    return r.ok() ? std::move(*r) : SceneProducts{};
  }();
  return p;
}

TEST(SceneOutputs, SameSeedGivesIdenticalBytes) {
  const fs::path a = temp_dir("a"), b = temp_dir("b");
  ASSERT_TRUE(write_scene(products(), a.string()).ok());
  auto again = render_scene(standard_scene_set()[5]);
  ASSERT_TRUE(again.ok());
  ASSERT_TRUE(write_scene(*again, b.string()).ok());
  for (const char* f : kFiles) {
    const std::string x = bytes(a / f), y = bytes(b / f);
    EXPECT_GT(x.size(), 100u) << f;
    EXPECT_TRUE(x == y) << f << " differs between two renders of one seed";
  }
}

TEST(SceneOutputs, OtherSeedsGiveOtherScenes) {
  SceneOptions o = standard_scene_set()[5];
  o.seed += 1;
  auto other = render_scene(o);
  ASSERT_TRUE(other.ok());
  EXPECT_NE(other->left.image.pixels, products().left.image.pixels);
  EXPECT_NE(other->truth_json, products().truth_json);
  EXPECT_NE(other->calib_json, products().calib_json);
  // Noise differs between the two cameras of one scene.
  EXPECT_NE(products().left.image.pixels, products().right.image.pixels);
}

TEST(SceneOutputs, AWindowRendersTheSamePixelsAsTheWholeImage) {
  const Rect win{400, 300, 150, 90};
  const RenderedView part = render_view(products().scene, Eye::right, win);
  for (int y = 0; y < 768; y += 3)
    for (int x = 0; x < 1024; x += 3) {
      const bool in = win.contains(x, y);
      ASSERT_EQ(part.image.view()(x, y), in ? products().right.image.view()(x, y) : 0) << x << "," << y;
      ASSERT_EQ(part.shadow_mask.view()(x, y), in ? products().right.shadow_mask.view()(x, y) : 0);
    }
}

TEST(SceneOutputs, FilesReadBackAsDocumented) {
  const fs::path d = temp_dir("read");
  const SceneProducts& p = products();
  ASSERT_TRUE(write_scene(p, d.string()).ok());
  // calib.json is the rig.
  auto rig = parse_calib_json(bytes(d / "calib.json"));
  ASSERT_TRUE(rig.ok()) << rig.error().message;
  EXPECT_EQ(rig->left.R, p.scene.rig.left.R);
  EXPECT_EQ(rig->right.T_mm, p.scene.rig.right.T_mm);
  EXPECT_EQ(rig->right.kappa1, p.scene.rig.right.kappa1);
  // truth.json carries the truth.
  auto truth = parse_truth_json(bytes(d / "truth.json"));
  ASSERT_TRUE(truth.ok()) << truth.error().message;
  EXPECT_EQ(truth->roi, p.truth.roi);
  EXPECT_EQ(truth->planes, p.scene.flat_faces);
  ASSERT_EQ(truth->facets.size(), p.truth.facets.size());
  for (std::size_t i = 0; i < truth->facets.size(); ++i) {
    EXPECT_TRUE(truth->facets[i].normal.isApprox(p.truth.facets[i].normal, 1e-12));
    EXPECT_EQ(truth->facets[i].centroid_mm, p.truth.facets[i].centroid);
    EXPECT_EQ(truth->facets[i].polygon_mm, p.truth.facets[i].polygon);
    EXPECT_EQ(truth->facets[i].grind_face, static_cast<int>(i) < truth->planes);
  }
  EXPECT_EQ(truth->seed, static_cast<long long>(p.scene.options.seed));
  EXPECT_TRUE(truth->ground_normal.isApprox(Eigen::Vector3d::UnitZ()));
  EXPECT_EQ(truth->ground_d_mm, 0.0);
  EXPECT_TRUE(truth->sun_dir.isApprox(p.scene.sun_dir, 1e-12));
  // The ROI holds the rock and its shadow with ground around them.
  const Rect& roi = truth->roi;
  EXPECT_TRUE(roi.inside(1024, 768));
  int shadow_in = 0, shadow_all = 0;
  for (int y = 0; y < 768; ++y)
    for (int x = 0; x < 1024; ++x)
      if (p.left.shadow_mask.view()(x, y)) {
        ++shadow_all;
        shadow_in += roi.contains(x, y) ? 1 : 0;
      }
  EXPECT_GT(shadow_all, 100);
  EXPECT_EQ(shadow_in, shadow_all);
  // Images and truth maps read back unchanged; PNG and PGM agree.
  for (const char* f : {"left.pgm", "left.png"}) {
    auto img = io::read_gray_image((d / f).string());
    ASSERT_TRUE(img.ok());
    EXPECT_EQ(img->pixels, p.left.image.pixels) << f;
  }
  auto disp = io::read_pfm((d / "disparity_truth.pfm").string());
  ASSERT_TRUE(disp.ok());
  ASSERT_EQ(disp->data.size(), p.rectified.disparity.data.size());
  int valid = 0;
  for (std::size_t i = 0; i < disp->data.size(); ++i) {
    const float v = disp->data[i], w = p.rectified.disparity.data[i];
    ASSERT_TRUE(v == w || (std::isinf(v) && std::isinf(w)));
    valid += std::isfinite(v) ? 1 : 0;
  }
  EXPECT_GT(valid, 500000);  // most of the view has a correspondence
  // disparity_range brackets the valid truth inside roi_rectified.
  EXPECT_LT(p.truth.disparity_min, p.truth.disparity_max);
  EXPECT_GT(p.truth.disparity_min, 50);
}

TEST(SceneOutputs, UnwritableDirectoryIsAnError) {
  const fs::path file = temp_dir("file");
  std::ofstream(file) << "x";
  auto st = write_scene(products(), file.string());
  ASSERT_FALSE(st.ok());
  EXPECT_NE(std::string(st.error().message).find("not a directory"), std::string::npos);
  auto st2 = write_scene(products(), (file / "sub").string());
  ASSERT_FALSE(st2.ok());
  fs::remove(file);
}

}  // namespace
}  // namespace petra::sim
