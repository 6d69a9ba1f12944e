// `petra sim scene` outputs: the same seed and options give identical bytes,
// other seeds give other scenes, and every file reads back as documented.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "algo/camera/calib_json.hpp"
#include "sim/scene/scene_render.hpp"
#include "sim/scene/scene_set.hpp"
#include "sim/score/truth_file.hpp"

namespace petra::sim {
namespace {

namespace fs = std::filesystem;

const char* const kFiles[] = {"left.pgm",
                              "right.pgm",
                              "left.png",
                              "right.png",
                              "calib.json",
                              "truth.json",
                              "disparity_truth.pfm",
                              "shadow_truth.pgm",
                              "shadow_truth_right.pgm",
                              "shadow_truth_rectified.pgm"};

std::string bytes(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}

fs::path temp_dir(const char* name) {
  // Per process: ctest runs the tests of this file in parallel processes.
  const fs::path d =
      fs::temp_directory_path() / ("petra_scene_" + std::to_string(getpid()) + "_" + name);
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
  auto a = make_scene(o);
  o.seed += 1;
  auto b = make_scene(o);
  ASSERT_TRUE(a.ok() && b.ok());
  const Rect win{440, 330, 140, 100};
  const RenderedView va = render_view(*a, Eye::left, win), vb = render_view(*b, Eye::left, win);
  EXPECT_NE(va.image.pixels, vb.image.pixels);
  EXPECT_NE(a->rig.left.R, b->rig.left.R);
  EXPECT_NE(a->rock_centre_mm, b->rock_centre_mm);
  // The two cameras of one scene get different noise.
  SceneOptions flat = standard_scene_set()[5];
  flat.texture = false;
  auto f = make_scene(flat);
  ASSERT_TRUE(f.ok());
  const Rect far{0, 0, 64, 32};  // distant ground: nearly uniform without texture
  const RenderedView fl = render_view(*f, Eye::left, far), fr = render_view(*f, Eye::right, far);
  EXPECT_NE(fl.image.pixels, fr.image.pixels);
}

// A pixel's value does not depend on which window is rendered.
TEST(SceneOutputs, AWindowRendersTheSamePixelsAsALargerOne) {
  auto s = make_scene(standard_scene_set()[5]);
  ASSERT_TRUE(s.ok());
  const Rect small{430, 320, 120, 80}, large{380, 280, 260, 170};
  const RenderedView a = render_view(*s, Eye::right, small), b = render_view(*s, Eye::right, large);
  int compared = 0;
  for (int y = 0; y < 768; ++y)
    for (int x = 0; x < 1024; ++x) {
      const bool in = small.contains(x, y);
      ASSERT_EQ(a.image.view()(x, y), in ? b.image.view()(x, y) : 0) << x << "," << y;
      ASSERT_EQ(a.shadow_mask.view()(x, y), in ? b.shadow_mask.view()(x, y) : 0);
      compared += in ? 1 : 0;
    }
  EXPECT_EQ(compared, small.w * small.h);
  EXPECT_GT(a.edge_pixels, 0);  // the window holds rock edges
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
  const SceneProducts nothing;  // the directory is checked before anything is written
  auto st = write_scene(nothing, file.string());
  ASSERT_FALSE(st.ok());
  EXPECT_NE(std::string(st.error().message).find("not a directory"), std::string::npos);
  auto st2 = write_scene(nothing, (file / "sub").string());
  ASSERT_FALSE(st2.ok());
  fs::remove(file);
}

}  // namespace
}  // namespace petra::sim
