// `petra stereo` end to end through its library function: real images in,
// PFM out, and every bad input rejected with a message naming it.
#include "sim/stereo/stereo_tool.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>

#include <unistd.h>

#include "algo/camera/calib_json.hpp"
#include "sim/eval/middlebury.hpp"
#include "sim/io/image_io.hpp"

namespace petra::stereo {
namespace {

const std::string kData = eval::default_data_root(PETRA_SOURCE_DIR) + "/middlebury/";
const std::string kDpTmp = ::testing::TempDir();

// ctest runs each test as its own process, in parallel: each writes its own file.
std::string test_out(const char* suffix) {
  return kDpTmp + "petra_stereo_" +
         ::testing::UnitTest::GetInstance()->current_test_info()->name() + "_" +
         std::to_string(::getpid()) + suffix;
}

struct RemoveAtEnd {
  std::string path;
  ~RemoveAtEnd() { std::remove(path.c_str()); }
};

StereoToolOptions tsukuba() {
  StereoToolOptions o;
  o.left = kData + "tsukuba/scene1.row3.col3.ppm";
  o.right = kData + "tsukuba/scene1.row3.col4.ppm";
  o.disp_min = 0;
  o.disp_max = 15;
  o.out = test_out(".pfm");
  return o;
}

TEST(StereoTool, WritesAFullSizePfmWithInfOutsideTheRoi) {
  StereoToolOptions o = tsukuba();
  const RemoveAtEnd cleanup{o.out};
  o.roi = "100,80,120,90";
  auto r = run_stereo_tool(o);
  ASSERT_TRUE(r.ok()) << r.error().message;
  auto pfm = io::read_pfm(o.out);
  ASSERT_TRUE(pfm.ok());
  EXPECT_EQ(pfm->width, 384);
  EXPECT_EQ(pfm->height, 288);
  long inside_valid = 0;
  for (int y = 0; y < 288; ++y)
    for (int x = 0; x < 384; ++x) {
      const float v = pfm->data[static_cast<std::size_t>(y) * 384 + x];
      const bool inside = x >= 100 && x < 220 && y >= 80 && y < 170;
      if (!inside)
        EXPECT_TRUE(std::isinf(v));
      else if (std::isfinite(v)) {
        ++inside_valid;
        EXPECT_GE(v, 0.0f);
        EXPECT_LE(v, 15.0f);
      }
    }
  EXPECT_EQ(inside_valid, r->stats.matched);
  EXPECT_GT(inside_valid, 120 * 90 * 8 / 10);
}

TEST(StereoTool, FillLeavesNoHoleInsideTheRoi) {
  StereoToolOptions o = tsukuba();
  const RemoveAtEnd cleanup{o.out};
  o.roi = "100,80,120,90";
  o.fill = true;
  ASSERT_TRUE(run_stereo_tool(o).ok());
  auto pfm = io::read_pfm(o.out);
  ASSERT_TRUE(pfm.ok());
  for (int y = 80; y < 170; ++y)
    for (int x = 100; x < 220; ++x)
      EXPECT_TRUE(std::isfinite(pfm->data[static_cast<std::size_t>(y) * 384 + x]));
}

TEST(StereoTool, ShadowFractionRemovesTheDarkestPixels) {
  StereoToolOptions o = tsukuba();
  const RemoveAtEnd cleanup{o.out};
  o.roi = "100,80,120,90";
  o.shadow_fraction = 0.25;
  auto r = run_stereo_tool(o);
  ASSERT_TRUE(r.ok()) << r.error().message;
  EXPECT_GE(r->stats.shadow_left, 120 * 90 / 4);
  EXPECT_LE(r->stats.matched, 120 * 90 - r->stats.shadow_left);
}

TEST(StereoTool, CalibRectifiesFirstAndMapsTheRoi) {
  // An already rectified rig (identical parallel cameras) keeps the images
  // and the ROI as they are, so the result equals the run without --calib.
  StereoRig rig;
  for (int k = 0; k < 2; ++k) {
    TsaiCamera& c = k == 0 ? rig.left : rig.right;
    c.width = 384;
    c.height = 288;
    c.f_mm = 4.0;
    c.dx_mm = c.dy_mm = 0.01;
    c.cx_px = 191.5;
    c.cy_px = 143.5;
    c.T_mm = Eigen::Vector3d(k == 0 ? 50.0 : -50.0, 0, 0);
  }
  char text[4096];
  auto n = format_calib_json(rig, std::span<char>(text, sizeof text));
  ASSERT_TRUE(n.ok());
  const std::string calib = kDpTmp + "petra_stereo_calib.json";
  ASSERT_TRUE(io::write_text_file(calib, std::string_view(text, *n)).ok());
  StereoToolOptions plain = tsukuba();
  const RemoveAtEnd cleanup{plain.out};
  plain.roi = "60,60,100,80";
  ASSERT_TRUE(run_stereo_tool(plain).ok());
  auto a = io::read_pfm(plain.out);
  StereoToolOptions rect = plain;
  rect.calib = calib;
  rect.out = kDpTmp + "petra_stereo_rect.pfm";
  auto r = run_stereo_tool(rect);
  ASSERT_TRUE(r.ok()) << r.error().message;
  EXPECT_EQ(r->roi, (Rect{60, 60, 100, 80}));
  auto b = io::read_pfm(rect.out);
  ASSERT_TRUE(a.ok() && b.ok());
  long same = 0, total = 0;
  for (std::size_t i = 0; i < a->data.size(); ++i) {
    if (!std::isfinite(a->data[i])) continue;
    ++total;
    same += std::isfinite(b->data[i]) && std::fabs(a->data[i] - b->data[i]) < 0.01f;
  }
  EXPECT_GT(static_cast<double>(same) / static_cast<double>(total), 0.99);
}

TEST(StereoTool, EveryBadInputIsRejectedWithItsName) {
  auto expect = [](StereoToolOptions o, const char* words) {
    std::remove(o.out.c_str());
    auto r = run_stereo_tool(o);
    ASSERT_FALSE(r.ok()) << words;
    EXPECT_NE(std::strstr(r.error().message, words), nullptr) << r.error().message;
    EXPECT_EQ(std::fopen(o.out.c_str(), "rb"), nullptr) << "nothing written on error";
  };
  StereoToolOptions o = tsukuba();
  o.out = kDpTmp + "petra_stereo_bad.pfm";
  StereoToolOptions a = o;
  a.roi = "300,200,200,200";
  expect(a, "outside");
  a.roi = "10,10,0,5";
  expect(a, "width and height");
  a.roi = "10,10,abc";
  expect(a, "x,y,w,h");
  StereoToolOptions b = o;
  b.disp_min = 200;
  b.disp_max = 250;
  b.roi = "0,0,100,100";
  expect(b, "outside the right image");
  StereoToolOptions c = o;
  c.right = kData + "teddy/im6.png";
  expect(c, "left image is 384x288 but right image is 450x375");
  StereoToolOptions d = o;
  d.left = kDpTmp + "petra_not_an_image.pgm";
  ASSERT_TRUE(io::write_text_file(d.left, "P5\n10 10\n255\nshort").ok());
  expect(d, "petra_not_an_image.pgm");
  StereoToolOptions e = o;
  e.left = kDpTmp + "petra_missing.png";
  expect(e, "petra_missing.png");
  StereoToolOptions f = o;
  f.method = "sgm";
  expect(f, "expected dp or gc");
  StereoToolOptions g = o;
  g.shadow_fraction = 1.5;
  expect(g, "fraction");
  StereoToolOptions h = o;
  h.calib = kDpTmp + "petra_bad_calib.json";
  ASSERT_TRUE(io::write_text_file(h.calib, "{\"model\":\"tsai-rac\"}").ok());
  expect(h, "missing");
  StereoToolOptions i = o;
  i.disp_min = 10;
  i.disp_max = 2;
  expect(i, "empty");
  // A textureless pair and an all-shadow ROI.
  io::GrayImage flat(64, 48, 128);
  StereoToolOptions j = o;
  j.left = j.right = kDpTmp + "petra_flat.pgm";
  ASSERT_TRUE(io::write_pgm(j.left, flat.view()).ok());
  expect(j, "textureless");
  j.shadow_fraction = 0.2;
  expect(j, "all shadow");
}

TEST(StereoTool, HandlesA1024x768PairWith128Disparities) {
  // The budget is sized for the problem: a whole 1024x768 pair, 128 disparities.
  auto l = io::read_gray_image(kData + "teddy/im2.png");
  auto r = io::read_gray_image(kData + "teddy/im6.png");
  ASSERT_TRUE(l.ok() && r.ok());
  io::GrayImage L(1024, 768), R(1024, 768);
  for (int y = 0; y < 768; ++y)
    for (int x = 0; x < 1024; ++x) {  // teddy scaled up 2x: disparities up to ~120
      L.view()(x, y) = l->view()(std::min(x / 2, 449), std::min(y / 2, 374));
      R.view()(x, y) = r->view()(std::min(x / 2, 449), std::min(y / 2, 374));
    }
  StereoToolOptions o;
  o.left = kDpTmp + "petra_big_l.pgm";
  o.right = kDpTmp + "petra_big_r.pgm";
  ASSERT_TRUE(io::write_pgm(o.left, L.view()).ok() && io::write_pgm(o.right, R.view()).ok());
  o.disp_min = 0;
  o.disp_max = 127;
  o.out = kDpTmp + "petra_big.pfm";
  auto res = run_stereo_tool(o);
  ASSERT_TRUE(res.ok()) << res.error().message;
  EXPECT_GT(res->stats.matched, 1024L * 768 / 2);
}

}  // namespace
}  // namespace petra::stereo
